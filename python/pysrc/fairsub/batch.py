"""Whole datasets: the jobs of a ``fairsub batch`` manifest, on this machine or on a Dask cluster.

``run(manifest, out)`` runs ``fairsub batch MANIFEST --out OUT`` (the same Rust coordinator:
worker processes, one per core, each job bounded in time and memory, results in
``OUT/results.jsonl``, a re-run skips what is done). ``run(manifest, out, client=client)``
runs the same jobs on a ``dask.distributed`` cluster: each job is one task that calls the
library in-process on a worker (through this package), the results stream back as they
finish, a task lost with its worker is run again by the scheduler, and the files are the
single-machine run's, byte for byte. The manifest and results formats, and a cluster recipe,
are in the user guide's batch page.

Example::

    import fairsub.batch
    from dask.distributed import Client, LocalCluster

    summary = fairsub.batch.run("manifest.jsonl", "out")                  # this machine
    with Client(LocalCluster(n_workers=2, threads_per_worker=1)) as client:
        summary = fairsub.batch.run("manifest.jsonl", "out", client=client)
    print(summary)   # {'ok': ..., 'error': ..., 'skipped': ..., 'seconds': ...}
"""

import json as _json
import os as _os
import sys as _sys
import time as _time
from typing import Any, Callable, Dict, Optional

from . import _fairsub

__all__ = ["run"]


def run(
    manifest: "str | os.PathLike[str]",
    out: "str | os.PathLike[str]",
    client: Any = None,
    jobs: Optional[int] = None,
    max_memory: Optional[int] = None,
    timeout: float = 600.0,
    on_row: Optional[Callable[[Dict[str, Any]], None]] = None,
) -> Dict[str, Any]:
    """Runs the jobs of ``manifest`` (JSON Lines or ``.csv``) into the folder ``out``.

    Without ``client``: ``fairsub batch``'s coordinator with ``jobs`` worker processes (default:
    one per core), ``max_memory`` bytes per job (default: half of what the process may use,
    shared by the jobs) and ``timeout`` seconds per job (0: none).

    With a ``dask.distributed.Client``: one task per job on its cluster (the paths must be
    the same on every worker: a shared file system). ``max_memory`` is the budget of each
    task's estimates (default: half of this machine's memory); the time limit does not apply
    there (a task cannot be stopped inside a worker; the cluster's own limits do).

    ``on_row`` is called with each result row (a dict) as it is written. Returns the counts
    ``{"ok", "error", "skipped", "seconds"}``; failed jobs are rows, not exceptions.
    """
    manifest = _os.path.abspath(_os.fspath(manifest))
    out = _os.path.abspath(_os.fspath(out))
    if client is None:
        if on_row is not None:
            raise ValueError("on_row needs a client (the command line's coordinator writes the rows)")
        worker = [_sys.executable, "-m", "fairsub._batch_worker"]
        summary = _fairsub.batch_run(manifest, out, worker, jobs, max_memory, timeout)
        return _json.loads(summary)
    return _run_on_cluster(client, manifest, out, max_memory, on_row)


def _run_task(task: str) -> str:
    """One job on a Dask worker: in-process, its files committed there; the outcome (JSON)."""
    from fairsub import _fairsub as lib

    return lib.batch_run_task(task)


def _failed(message: str) -> str:
    """The outcome of a task that the cluster could not run."""
    return _json.dumps(
        {"error": message, "seconds": 0.0, "counts": {}, "metrics": None, "notes": [], "staged": [], "outputs": []}
    )


def _run_on_cluster(client, manifest, out, max_memory, on_row):
    from distributed import as_completed

    start = _time.monotonic()
    _os.makedirs(out, exist_ok=True)
    lock = _lock(out)
    try:
        budget = max_memory if max_memory is not None else _fairsub.batch_default_budget(1)
        plan_json = _fairsub.batch_plan(manifest, out, budget)
        plan = _json.loads(plan_json)
        counts = {"ok": 0, "error": 0, "skipped": 0}

        def write(rows):
            _fairsub.batch_append(out, [_json.dumps(r) for r in rows])
            for r in rows:
                counts[r["status"]] += 1
                if on_row is not None:
                    on_row(r)

        write(plan["settled"])
        todo = plan["todo"]
        futures = {}
        for p in todo:
            task = _json.dumps(p["task"])
            # a key per job (line and output) so that the scheduler tracks and retries it
            key = "fairsub-batch-%d-%s" % (p["task"]["line"], _os.path.basename(str(p["row"]["output"])))
            futures[client.submit(_run_task, task, key=key, pure=False)] = p
        for future in as_completed(futures):
            p = futures.pop(future)
            try:
                outcome = future.result()
            except Exception as e:  # a task the cluster gave up on (lost with its workers)
                outcome = _failed("the cluster could not run the job: %s: %s" % (type(e).__name__, e))
            row = _json.loads(_fairsub.batch_settle(_json.dumps(p["row"]), outcome))
            write([row])
        # every task has ended: what a killed worker left half-written is removed
        _fairsub.batch_remove_temps(plan_json)
    finally:
        lock.close()
    counts["seconds"] = _time.monotonic() - start
    return counts


def _lock(out):
    """Holds ``out/.fairsub-batch.lock`` (the command line's lock) for the run."""
    f = open(_os.path.join(out, ".fairsub-batch.lock"), "a")
    try:
        import fcntl

        fcntl.flock(f.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
    except ImportError:  # no flock on this platform
        pass
    except OSError:
        f.close()
        raise ValueError("another fairsub batch is writing into %s" % out) from None
    return f
