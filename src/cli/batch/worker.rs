//! The worker processes of `fairsub batch`: one per job slot, each running its jobs one after
//! another in-process ([`super::job::run`]), fed tasks as JSON lines on its standard input and
//! answering with one outcome line each on its standard output.
//!
//! Why processes and not threads: a job must stop when it runs over its time or memory, and
//! a Rust thread cannot be stopped from outside; cooperative checks would have to sit in
//! every long loop of the library (refinement, caps, tessellation, writers), and one missed
//! loop would keep a core busy and could write its output after its error row. An allocation
//! over a hard limit aborts the whole process (Rust cannot unwind out of an allocation
//! failure). A process can be killed, and its memory limited by the kernel: so the slot kills
//! a worker that runs over `--timeout` and starts a new one, and each worker caps its address
//! space at its size after start-up plus twice the job's budget, at least 256 MiB (the budget
//! counts the large arrays; the estimates refuse most jobs over it before they allocate). The
//! workers live for the whole run, so their start-up (a few milliseconds) is paid once per
//! slot, not per job.

use super::job::{self, Outcome, Task};
use crate::error::{Error, Result};
use std::collections::VecDeque;
use std::ffi::OsString;
use std::io::{BufRead, BufReader, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// Serves tasks: one JSON task per input line, one JSON outcome per output line, until the
/// input ends (`fairsub batch-worker`, and the Python package's worker module).
///
/// # Errors
/// [`Error::Io`] when the pipes fail; [`Error::InvalidArgument`] for a line that is not a task.
pub fn serve(input: impl BufRead, mut output: impl Write) -> Result<()> {
    let io = |source| Error::Io {
        path: "the worker's pipe".into(),
        source,
    };
    let mut limited = false;
    for line in input.lines() {
        let line = line.map_err(io)?;
        let task: Task = serde_json::from_str(&line)
            .map_err(|e| Error::InvalidArgument(format!("not a batch task: {e}")))?;
        if !limited {
            // the thread pool's stacks are reserved before the cap: started lazily under a
            // small cap, the pool failed to start and every job of the worker with it
            rayon::current_num_threads();
            cap_address_space(task.budget);
            limited = true;
        }
        let outcome = job::run(&task);
        let mut text = serde_json::to_string(&outcome).expect("serialisable");
        text.push('\n');
        output.write_all(text.as_bytes()).map_err(io)?;
        output.flush().map_err(io)?;
    }
    Ok(())
}

/// The least room a worker's address space keeps above its size at start-up, whatever the
/// budget: the parsing, the hash maps and the output buffers of a job that the estimates
/// (which count the large arrays) let through must fit.
const MIN_HEADROOM: u64 = 256 << 20;

/// Caps this process's address space at its present size plus twice `budget`, and at least
/// [`MIN_HEADROOM`] more (Linux; a no-op elsewhere): the kernel then refuses what a job would
/// take beyond it, and the process stops.
fn cap_address_space(budget: u64) {
    #[cfg(target_os = "linux")]
    {
        let Some(pages) = std::fs::read_to_string("/proc/self/statm")
            .ok()
            .and_then(|s| s.split_whitespace().next()?.parse::<u64>().ok())
        else {
            return;
        };
        // SAFETY: sysconf reads a system parameter.
        let page = unsafe { libc::sysconf(libc::_SC_PAGESIZE) }.max(4096) as u64;
        let limit = (pages * page).saturating_add(budget.saturating_mul(2).max(MIN_HEADROOM));
        let mut r = libc::rlimit {
            rlim_cur: 0,
            rlim_max: 0,
        };
        // SAFETY: getrlimit and setrlimit read and write this process's limits.
        unsafe {
            if libc::getrlimit(libc::RLIMIT_AS, &mut r) == 0
                && (r.rlim_cur == libc::RLIM_INFINITY || r.rlim_cur > limit)
            {
                r.rlim_cur = limit.min(r.rlim_max);
                libc::setrlimit(libc::RLIMIT_AS, &r);
            }
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = budget;
}

/// How many lines of a worker's standard error are kept for the message of a job it died on.
const STDERR_TAIL: usize = 8;

/// A running worker process.
pub struct Worker {
    child: Child,
    stdin: Option<ChildStdin>,
    lines: Receiver<std::io::Result<String>>,
    tail: Arc<Mutex<VecDeque<String>>>,
}

impl Worker {
    /// Starts `command` (program and arguments) as a worker: one thread of its own for the
    /// library's parallel loops (the slots are the parallelism).
    pub fn spawn(command: &[OsString]) -> Result<Worker> {
        let (program, args) = command
            .split_first()
            .ok_or_else(|| Error::InvalidArgument("empty worker command".into()))?;
        let mut child = Command::new(program)
            .args(args)
            .env("RAYON_NUM_THREADS", "1")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|source| Error::Io {
                path: program.into(),
                source,
            })?;
        let (tx, lines) = channel();
        let stdout = child.stdout.take().expect("piped");
        std::thread::spawn(move || {
            for l in BufReader::new(stdout).lines() {
                if tx.send(l).is_err() {
                    break;
                }
            }
        });
        let tail = Arc::new(Mutex::new(VecDeque::new()));
        let stderr = child.stderr.take().expect("piped");
        let t = Arc::clone(&tail);
        std::thread::spawn(move || {
            for l in BufReader::new(stderr).lines().map_while(|l| l.ok()) {
                let mut q = t.lock().unwrap_or_else(|e| e.into_inner());
                if q.len() == STDERR_TAIL {
                    q.pop_front();
                }
                q.push_back(l);
            }
        });
        Ok(Worker {
            stdin: child.stdin.take(),
            child,
            lines,
            tail,
        })
    }

    /// Runs a task with a time limit (`None`: none). `Err` is the message of a job whose
    /// worker had to be stopped or died: the worker is then gone.
    pub fn run(
        &mut self,
        task: &Task,
        limit: Option<Duration>,
    ) -> std::result::Result<Outcome, String> {
        self.tail.lock().unwrap_or_else(|e| e.into_inner()).clear();
        let mut line = serde_json::to_string(task).expect("serialisable");
        line.push('\n');
        let sent = self
            .stdin
            .as_mut()
            .is_some_and(|s| s.write_all(line.as_bytes()).and_then(|_| s.flush()).is_ok());
        if !sent {
            return Err(self.died());
        }
        let got = match limit {
            Some(l) => self.lines.recv_timeout(l),
            None => self
                .lines
                .recv()
                .map_err(|_| RecvTimeoutError::Disconnected),
        };
        match got {
            Ok(Ok(l)) => serde_json::from_str(&l)
                .map_err(|e| format!("the worker answered what is not an outcome ({e}): {l}")),
            Err(RecvTimeoutError::Timeout) => {
                let _ = self.child.kill();
                let _ = self.child.wait();
                let secs = limit.map_or(0.0, |l| l.as_secs_f64());
                Err(format!(
                    "stopped after the time limit of {secs} s (--timeout): the job ran longer"
                ))
            }
            _ => Err(self.died()),
        }
    }

    /// The message of a worker that died under a job (its exit, and its last words).
    fn died(&mut self) -> String {
        let _ = self.child.kill();
        let status = self.child.wait();
        // the stderr thread may still be reading the last words
        std::thread::sleep(Duration::from_millis(20));
        let tail: Vec<String> = self
            .tail
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .iter()
            .cloned()
            .collect();
        let how = match status {
            Ok(s) => describe_exit(s),
            Err(e) => format!("could not be waited for ({e})"),
        };
        let words = tail.join(" | ");
        let memory = words.contains("memory allocation");
        format!(
            "the worker process running the job {how}{}{}",
            if words.is_empty() {
                String::new()
            } else {
                format!("; its last words: {words}")
            },
            if memory {
                " (the job went over its hard memory limit: twice --max-memory per job; \
                 raise --max-memory or use fewer --jobs)"
            } else {
                ""
            }
        )
    }
}

/// How a process ended, in words.
fn describe_exit(s: std::process::ExitStatus) -> String {
    #[cfg(unix)]
    {
        use std::os::unix::process::ExitStatusExt;
        if let Some(sig) = s.signal() {
            let name = match sig {
                libc::SIGABRT => " (abort)",
                libc::SIGKILL => " (killed)",
                libc::SIGSEGV => " (segmentation fault)",
                _ => "",
            };
            return format!("was ended by signal {sig}{name}");
        }
    }
    match s.code() {
        Some(c) => format!("exited with code {c}"),
        None => "ended".into(),
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        // end of input: the worker finishes and exits; one that does not is killed
        drop(self.stdin.take());
        for _ in 0..100 {
            if let Ok(Some(_)) = self.child.try_wait() {
                return;
            }
            std::thread::sleep(Duration::from_millis(10));
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
