//! `fairsub batch MANIFEST --out DIR`: many jobs of `fairsub subdivide` (and their metrics)
//! from a manifest, in parallel, each bounded in time and memory, with one result row per job
//! in `DIR/results.jsonl` and resuming where an earlier run left off.
//!
//! | module | holds |
//! | --- | --- |
//! | `manifest` | the JSON Lines / CSV manifest, read into jobs with resolved paths and the command line's words |
//! | `results` | the rows of `results.jsonl`, the jobs' content hashes, the resume index |
//! | `job` | one job run in-process by `subdivide`'s own code, its writes staged |
//! | `worker` | the worker processes (one per slot) and why they are processes |
//!
//! The run: [`plan`] reads the manifest and the earlier results (jobs whose key and outputs
//! are unchanged are skipped, bad lines become error rows), the slots feed the other jobs to
//! their workers, and the coordinator commits the finished jobs' files in groups
//! ([`crate::io::commit`]: one sync for a group, then the renames) before appending their
//! rows. The Python package runs the same plan and the same jobs on a Dask cluster.

mod job;
mod manifest;
mod results;
mod worker;

pub use job::{Outcome, Task};
pub use results::{OutputFile, RESULTS, Row, Status};
pub use worker::serve;

use crate::error::{Error, Result};
use std::collections::{HashMap, VecDeque};
use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::sync::mpsc::{RecvTimeoutError, channel};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// Arguments of `fairsub batch`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The manifest: JSON Lines, one job a line (`{"input": "net.obj", "scheme": "eg",
    /// "rings": 4, "output": "net.bv"}`), or CSV with the same column names (`.csv`).
    pub manifest: PathBuf,
    /// Folder of the outputs and of results.jsonl (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Jobs at once, each in its own worker process (default: one per core).
    #[arg(long, short)]
    pub jobs: Option<usize>,
    /// Seconds a job may take; one that runs longer is stopped and gets an error row
    /// (0: no limit).
    #[arg(long, default_value_t = 600.0, value_name = "SECONDS")]
    pub timeout: f64,
}

/// A job to run: its row so far (line, input, output, key) and its task.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct Planned {
    /// The row, to be completed by [`settle`].
    pub row: Row,
    /// What the worker runs.
    pub task: Task,
}

/// What a run has to do: the jobs to run, and the rows already settled (manifest errors,
/// duplicate outputs, jobs skipped as done).
#[derive(Debug, Clone, Default, serde::Serialize, serde::Deserialize)]
pub struct Plan {
    /// Jobs to run.
    pub todo: Vec<Planned>,
    /// Rows without work.
    pub settled: Vec<Row>,
    /// Lines of the earlier `results.jsonl` that are not rows (ignored).
    pub unreadable: Vec<usize>,
}

/// Reads the manifest and the earlier results in `out` and plans the run with `budget` bytes
/// per job; creates `out` and the outputs' folders, and removes temporary files that a
/// stopped run left beside the outputs (call it only while no other run writes into `out`).
///
/// # Errors
/// A manifest that cannot be read, or an `out` that cannot be made.
pub fn plan(manifest: &Path, out: &Path, budget: u64) -> Result<Plan> {
    mkdir(out)?;
    let entries = manifest::read(manifest)?;
    if entries.is_empty() {
        return Err(manifest::empty(manifest));
    }
    let done = results::Done::read(out)?;
    let mut plan = Plan {
        unreadable: done.unreadable.clone(),
        ..Plan::default()
    };
    let mut seen: HashMap<PathBuf, usize> = HashMap::new();
    for e in entries {
        let job = match e {
            Ok(j) => j,
            Err(l) => {
                plan.settled
                    .push(Row::error(l.line, l.input, l.output, l.message));
                continue;
            }
        };
        let error =
            |m: String| Row::error(job.line, Some(job.input.clone()), job.output.clone(), m);
        let target = job.output.as_ref().map(|o| out.join(o));
        if let Some(t) = &target {
            let norm: PathBuf = t.components().collect();
            if let Some(l) = seen.insert(norm, job.line) {
                plan.settled.push(error(format!(
                    "output '{}' is written by line {l} already",
                    job.output.as_deref().unwrap_or_default()
                )));
                continue;
            }
            crate::io::remove_stale_temps(t);
            if let Err(e) = t.parent().map_or(Ok(()), mkdir) {
                plan.settled.push(error(e.to_string()));
                continue;
            }
        }
        let key = results::job_key(&job);
        if let Some(prev) = key.as_deref().and_then(|k| done.intact(k, out)) {
            plan.settled.push(Row {
                line: job.line,
                input: Some(job.input.clone()),
                output: job.output.clone(),
                status: Status::Skipped,
                seconds: 0.0,
                ..prev.clone()
            });
            continue;
        }
        let mut row = error(String::new());
        (row.status, row.error, row.key) = (Status::Ok, None, key);
        let measured = job.measure.then(|| {
            let mut m = job.clone();
            (m.levels, m.output) = (None, None);
            m.rings = Some(job.rings.unwrap_or(job::MEASURE_RINGS));
            m.options
                .retain(|(k, _)| !matches!(k.as_str(), "limit" | "tess" | "format"));
            m.words(out)
        });
        let task = Task {
            line: job.line,
            write: job.output.is_some().then(|| job.words(out)),
            measure: measured,
            input: job.input.clone(),
            output: target,
            out: out.to_path_buf(),
            budget,
        };
        plan.todo.push(Planned { row, task });
    }
    Ok(plan)
}

/// The default memory budget of a job when `slots` jobs run at once: the command line's
/// default budget (half of what the process may use) shared by the slots.
pub fn default_budget(slots: usize) -> u64 {
    (super::limits::default_budget().bytes / slots.max(1) as f64) as u64
}

/// Appends rows to `DIR/results.jsonl` (one write per row, then a sync).
///
/// # Errors
/// [`Error::Io`] when the file cannot be opened or written.
pub fn append_rows(out: &Path, rows: &[Row]) -> Result<()> {
    results::Log::open(out)?.append(rows)
}

/// Removes what stopped jobs left of their outputs' temporary files (call it when no job of
/// `plan` runs any more).
pub fn remove_stale_temps(plan: &[Planned]) {
    for p in plan {
        if let Some(t) = &p.task.output {
            crate::io::remove_stale_temps(t);
        }
    }
}

/// Creates a folder (and its parents).
fn mkdir(d: &Path) -> Result<()> {
    std::fs::create_dir_all(d).map_err(|source| Error::Io {
        path: d.to_path_buf(),
        source,
    })
}

/// The row of a job from its planned row and what it did (its files committed).
pub fn settle(mut row: Row, o: Outcome) -> Row {
    row.seconds = o.seconds;
    match o.error {
        Some(e) => {
            row.status = Status::Error;
            row.error = Some(e);
            row.key = None;
        }
        None => {
            row.status = Status::Ok;
            row.outputs = o.outputs;
            row.counts = o.counts;
            row.metrics = o.metrics;
            row.notes = o.notes;
        }
    }
    row
}

/// Runs a task in this thread and commits its files (each synced on its own): what a task on
/// a cluster does, where no coordinator shares the file system.
pub fn run_and_commit(task: &Task) -> Outcome {
    let mut o = job::run(task);
    commit_outcomes(
        std::slice::from_mut(&mut o),
        crate::io::Durability::EachFile,
    );
    o
}

/// Commits the staged files of outcomes: all in one group, or (when that fails) each job's
/// on its own, so that a failure is charged to its job.
fn commit_outcomes(outcomes: &mut [Outcome], how: crate::io::Durability) {
    let staged = |o: &Outcome| -> Vec<crate::io::Staged> {
        o.staged
            .iter()
            .map(|(temp, target)| crate::io::Staged {
                temp: temp.clone(),
                target: target.clone(),
            })
            .collect()
    };
    let all: Vec<_> = outcomes.iter().flat_map(staged).collect();
    if crate::io::commit(&all, how).is_ok() {
        outcomes.iter_mut().for_each(|o| o.staged.clear());
        return;
    }
    for o in outcomes.iter_mut() {
        let files = staged(o);
        if let Err(e) = crate::io::commit(&files, crate::io::Durability::EachFile) {
            crate::io::discard(&files);
            o.error = Some(e.to_string());
        }
        o.staged.clear();
    }
}

/// What a run did.
#[derive(Debug, Clone, Default, serde::Serialize)]
pub struct Summary {
    /// Jobs done in this run.
    pub ok: usize,
    /// Jobs (and manifest lines) that failed.
    pub error: usize,
    /// Jobs skipped as done.
    pub skipped: usize,
    /// Wall-clock seconds of the run.
    pub seconds: f64,
}

impl Summary {
    fn count(&mut self, r: &Row) {
        match r.status {
            Status::Ok => self.ok += 1,
            Status::Error => self.error += 1,
            Status::Skipped => self.skipped += 1,
        }
    }
}

/// Runs `fairsub batch`: exits with an error when a job failed (after all ran).
pub fn run(a: Args) -> Result<()> {
    let exe = std::env::current_exe().map_err(|source| Error::Io {
        path: "the fairsub executable".into(),
        source,
    })?;
    let worker = [exe.into_os_string(), "batch-worker".into()];
    let s = run_with(&a, &worker, super::limits::max_memory())?;
    if s.error > 0 {
        return Err(Error::InvalidArgument(format!(
            "{} of {} jobs failed; their rows in {} say why",
            s.error,
            s.ok + s.error + s.skipped,
            a.out.join(RESULTS).display()
        )));
    }
    Ok(())
}

/// Outcomes committed at once, at most.
const GROUP: usize = 64;

/// The longest a finished job waits for its group's commit.
const GROUP_WAIT: Duration = Duration::from_millis(500);

/// Runs a batch with `worker` as the command of the worker processes (the `fairsub` binary's
/// `batch-worker`, or the Python package's worker module); the budget per job is
/// `max_memory` (bytes), or the default budget shared by the slots.
pub fn run_with(a: &Args, worker: &[OsString], max_memory: Option<u64>) -> Result<Summary> {
    let start = Instant::now();
    let slots = a
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
        .max(1);
    let budget = max_memory.unwrap_or_else(|| default_budget(slots));
    mkdir(&a.out)?;
    let _lock = lock(&a.out)?;
    let plan = plan(&a.manifest, &a.out, budget)?;
    if !plan.unreadable.is_empty() {
        eprintln!(
            "warning: {}: line(s) {:?} are not result rows; ignored (their jobs run again)",
            a.out.join(RESULTS).display(),
            plan.unreadable
        );
    }
    let mut log = results::Log::open(&a.out)?;
    let mut summary = Summary::default();
    plan.settled.iter().for_each(|r| summary.count(r));
    log.append(&plan.settled)?;
    let total = (plan.settled.len() + plan.todo.len()) as u64;
    let pb = progress(total, plan.settled.len() as u64);
    let rows: Vec<Row> = plan.todo.iter().map(|p| p.row.clone()).collect();
    let queue: VecDeque<(usize, Task)> =
        plan.todo.into_iter().map(|p| p.task).enumerate().collect();
    let queue = Arc::new(Mutex::new(queue));
    let limit = (a.timeout > 0.0).then(|| Duration::from_secs_f64(a.timeout));
    let (tx, rx) = channel::<(usize, Outcome)>();
    let threads: Vec<_> = (0..slots.min(rows.len()))
        .map(|_| {
            let (queue, tx, worker) = (Arc::clone(&queue), tx.clone(), worker.to_vec());
            std::thread::spawn(move || slot(&queue, &tx, &worker, limit))
        })
        .collect();
    drop(tx);
    let mut pending: Vec<(usize, Outcome)> = Vec::new();
    let mut since = Instant::now();
    loop {
        let wait = GROUP_WAIT.saturating_sub(since.elapsed());
        let got = rx.recv_timeout(if pending.is_empty() { GROUP_WAIT } else { wait });
        let closed = matches!(got, Err(RecvTimeoutError::Disconnected));
        if let Ok(d) = got {
            if pending.is_empty() {
                since = Instant::now();
            }
            pending.push(d);
        }
        let due = pending.len() >= GROUP || since.elapsed() >= GROUP_WAIT || closed;
        if due && !pending.is_empty() {
            let mut outcomes: Vec<Outcome> = pending.iter().map(|(_, o)| o.clone()).collect();
            commit_outcomes(&mut outcomes, crate::io::Durability::FileSystem);
            let done: Vec<Row> = pending
                .drain(..)
                .zip(outcomes)
                .map(|((i, _), o)| settle(rows[i].clone(), o))
                .collect();
            done.iter().for_each(|r| summary.count(r));
            log.append(&done)?;
            pb.inc(done.len() as u64);
            if summary.error > 0 {
                pb.set_message(format!("batch ({} failed)", summary.error));
            }
        }
        if closed {
            break;
        }
    }
    for t in threads {
        let _ = t.join();
    }
    pb.finish_and_clear();
    summary.seconds = start.elapsed().as_secs_f64();
    let ran = summary.ok + summary.error;
    eprintln!(
        "batch: {} ok, {} failed, {} skipped in {:.1} s ({:.1} jobs/s); results in {}",
        summary.ok,
        summary.error,
        summary.skipped,
        summary.seconds,
        ran as f64 / summary.seconds.max(1e-9),
        a.out.join(RESULTS).display()
    );
    Ok(summary)
}

/// A slot: takes tasks off the queue and runs them on its worker, starting a new worker when
/// the last one was stopped or died.
fn slot(
    queue: &Mutex<VecDeque<(usize, Task)>>,
    tx: &std::sync::mpsc::Sender<(usize, Outcome)>,
    command: &[OsString],
    limit: Option<Duration>,
) {
    let mut w: Option<worker::Worker> = None;
    loop {
        let next = queue.lock().unwrap_or_else(|e| e.into_inner()).pop_front();
        let Some((i, task)) = next else {
            return;
        };
        let start = Instant::now();
        let outcome = match w.take().map_or_else(|| worker::Worker::spawn(command), Ok) {
            Err(e) => Err(format!("could not start a worker process: {e}")),
            Ok(mut wk) => {
                let r = wk.run(&task, limit);
                if r.is_ok() {
                    w = Some(wk);
                }
                r
            }
        };
        let outcome = outcome.unwrap_or_else(|message| {
            // a stopped worker leaves its temporary files behind
            if let Some(t) = &task.output {
                crate::io::remove_stale_temps(t);
            }
            Outcome {
                error: Some(message),
                seconds: start.elapsed().as_secs_f64(),
                ..Outcome::default()
            }
        });
        if tx.send((i, outcome)).is_err() {
            return;
        }
    }
}

/// The progress bar of a run: done jobs, rate and time left (drawn only on a terminal).
fn progress(total: u64, done: u64) -> indicatif::ProgressBar {
    let pb = indicatif::ProgressBar::new(total);
    if let Ok(style) = indicatif::ProgressStyle::with_template(
        "{msg} [{bar:30}] {pos}/{len} jobs, {per_sec}, {eta} left",
    ) {
        pb.set_style(style.progress_chars("=> "));
    }
    pb.set_message("batch");
    pb.set_position(done);
    pb.reset_eta();
    pb
}

/// Holds `DIR/.fairsub-batch.lock` for the run: a second run into the same folder stops at
/// once instead of writing beside the first.
fn lock(out: &Path) -> Result<std::fs::File> {
    let path = out.join(".fairsub-batch.lock");
    let f = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&path)
        .map_err(|source| Error::Io {
            path: path.clone(),
            source,
        })?;
    #[cfg(unix)]
    {
        use std::os::fd::AsRawFd;
        // SAFETY: flock on a descriptor `f` owns; released when `f` is closed.
        if unsafe { libc::flock(f.as_raw_fd(), libc::LOCK_EX | libc::LOCK_NB) } != 0 {
            return Err(Error::InvalidArgument(format!(
                "another fairsub batch is writing into {} (it holds {})",
                out.display(),
                path.display()
            )));
        }
    }
    Ok(f)
}
