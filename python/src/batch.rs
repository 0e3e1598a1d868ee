//! `fairsub.batch`'s entry points (`python/pysrc/fairsub/batch.py`): the plan, the tasks and
//! the rows of `fairsub batch` (`fairsub::cli::batch`) as JSON strings, so that a Dask cluster
//! runs the very jobs the command line runs, in-process on its workers; and the command
//! line's own coordinator, with the package's worker module as its worker processes.

use fairsub::cli::batch;
use pyo3::prelude::*;
use std::path::PathBuf;

use super::err;

/// JSON of a serialisable value.
macro_rules! json {
    ($v:expr) => {
        serde_json::to_string($v).expect("serialisable")
    };
}

/// A value of type `$t` from JSON `$text`, or ValueError.
macro_rules! parse {
    ($t:ty, $text:expr, $what:expr) => {
        serde_json::from_str::<$t>($text).map_err(|e| {
            pyo3::exceptions::PyValueError::new_err(format!("not a batch {}: {e}", $what))
        })
    };
}

/// The plan of a run (JSON: `todo` [{row, task}], `settled` rows, `unreadable` lines):
/// manifest read, earlier results of `out` consulted, `budget` bytes per job.
#[pyfunction]
fn batch_plan(py: Python<'_>, manifest: PathBuf, out: PathBuf, budget: u64) -> PyResult<String> {
    py.detach(|| batch::plan(&manifest, &out, budget))
        .map(|p| json!(&p))
        .map_err(err)
}

/// Runs one task in this process and commits its files; the outcome as JSON (a failed job is
/// an outcome with `error`, never an exception).
#[pyfunction]
fn batch_run_task(py: Python<'_>, task: &str) -> PyResult<String> {
    let task = parse!(batch::Task, task, "task")?;
    Ok(json!(&py.detach(|| batch::run_and_commit(&task))))
}

/// The row of a planned job (`row`, JSON) from its outcome (JSON).
#[pyfunction]
fn batch_settle(row: &str, outcome: &str) -> PyResult<String> {
    Ok(json!(&batch::settle(
        parse!(batch::Row, row, "row")?,
        parse!(batch::Outcome, outcome, "outcome")?,
    )))
}

/// Appends rows (JSON strings) to `out`/results.jsonl.
#[pyfunction]
fn batch_append(py: Python<'_>, out: PathBuf, rows: Vec<String>) -> PyResult<()> {
    let rows = rows
        .iter()
        .map(|r| parse!(batch::Row, r, "row"))
        .collect::<PyResult<Vec<batch::Row>>>()?;
    py.detach(|| batch::append_rows(&out, &rows)).map_err(err)
}

/// Removes the temporary files that stopped jobs of a plan (JSON) left.
#[pyfunction]
fn batch_remove_temps(plan: &str) -> PyResult<()> {
    let plan = parse!(batch::Plan, plan, "plan")?;
    batch::remove_stale_temps(&plan.todo);
    Ok(())
}

/// The default budget of a job when `slots` run at once (bytes).
#[pyfunction]
fn batch_default_budget(slots: usize) -> u64 {
    batch::default_budget(slots)
}

/// Runs `fairsub batch` with `worker` (program and arguments) as the worker processes; the
/// summary as JSON.
#[pyfunction]
#[pyo3(signature = (manifest, out, worker, jobs=None, max_memory=None, timeout=600.0))]
fn batch_run(
    py: Python<'_>,
    manifest: PathBuf,
    out: PathBuf,
    worker: Vec<String>,
    jobs: Option<usize>,
    max_memory: Option<u64>,
    timeout: f64,
) -> PyResult<String> {
    let args = batch::Args {
        manifest,
        out,
        jobs,
        timeout,
    };
    let worker: Vec<std::ffi::OsString> = worker.into_iter().map(Into::into).collect();
    py.detach(|| batch::run_with(&args, &worker, max_memory))
        .map(|s| json!(&s))
        .map_err(err)
}

/// Serves tasks on this process's standard input and output (the worker module).
#[pyfunction]
fn batch_serve(py: Python<'_>) -> PyResult<()> {
    py.detach(|| batch::serve(std::io::stdin().lock(), std::io::stdout().lock()))
        .map_err(err)
}

/// Adds the batch functions to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(batch_plan, m)?)?;
    m.add_function(wrap_pyfunction!(batch_run_task, m)?)?;
    m.add_function(wrap_pyfunction!(batch_settle, m)?)?;
    m.add_function(wrap_pyfunction!(batch_append, m)?)?;
    m.add_function(wrap_pyfunction!(batch_remove_temps, m)?)?;
    m.add_function(wrap_pyfunction!(batch_default_budget, m)?)?;
    m.add_function(wrap_pyfunction!(batch_run, m)?)?;
    m.add_function(wrap_pyfunction!(batch_serve, m)?)?;
    Ok(())
}
