"""fairsub.batch: the jobs of a manifest through the package, without a client (the command
line's coordinator with the package's worker processes) and on a Dask LocalCluster of 2 worker
processes with one of them killed in the middle of the run. Both give the files of `fairsub
batch` byte for byte, one row per job, and nothing half-written."""

import json
import os
import pathlib
import signal
import subprocess

import pytest

import fairsub.batch
from conftest import cli_path


def grid_obj(w, h, seed):
    """A w x h grid of quads with a bump that depends on seed, as OBJ text."""
    lines = []
    for j in range(h + 1):
        for i in range(w + 1):
            lines.append("v %d %d %g" % (i, j, ((i * 7 + j * 3 + seed) % 11) / 10))
    for j in range(h):
        for i in range(w):
            a = j * (w + 1) + i + 1
            lines.append("f %d %d %d %d" % (a, a + 1, a + w + 2, a + w + 1))
    return "\n".join(lines) + "\n"


def make_manifest(d: pathlib.Path, heavy=0):
    """A manifest of gallery and generated nets, a few bad jobs and `heavy` slower ones."""
    nets = d / "nets"
    nets.mkdir(parents=True, exist_ok=True)
    jobs = []
    for g in ["cube", "tetrahedron", "torus-evs", "cnet-5-saddle", "cnet-6-convex"]:
        jobs.append({"input": "gallery:" + g, "scheme": "catmull-clark", "levels": 2, "output": "g/%s.obj" % g})
        jobs.append({"input": "gallery:" + g, "scheme": "doo-sabin", "levels": 2, "output": "g/%s.off" % g})
        jobs.append({"input": "gallery:" + g, "scheme": "catmull-clark", "rings": 3, "output": "g/%s.bv" % g,
                     "measure": True})
    for seed in range(40):
        (nets / ("grid%d.obj" % seed)).write_text(grid_obj(2 + seed % 3, 2 + seed % 2, seed))
        jobs.append({"input": "nets/grid%d.obj" % seed, "scheme": "catmull-clark", "levels": 1 + seed % 2,
                     "output": "grids/%d.ply" % seed, "options": {"boundary": "edge-only"}})
    for k in range(heavy):
        jobs.append({"input": "gallery:torus-evs", "scheme": "catmull-clark", "levels": 5,
                     "output": "heavy/%d.obj" % k, "options": {"limit": k % 2 == 0}})
    (nets / "corrupt.obj").write_text("v 0 0 0\nv 1 0 0\nf 1 2 7\n")
    jobs.append({"input": "nets/corrupt.obj", "scheme": "catmull-clark", "levels": 1, "output": "bad/c.obj"})
    jobs.append({"input": "gallery:cube", "scheme": "catmull-clark", "levels": 14, "output": "bad/big.obj"})
    path = d / "manifest.jsonl"
    path.write_text("".join(json.dumps(j) + "\n" for j in jobs))
    return path, len(jobs)


def files(out: pathlib.Path):
    """Every file under out (relative name -> bytes), except the results and the lock."""
    found = {}
    for p in out.rglob("*"):
        rel = p.relative_to(out).as_posix()
        if p.is_file() and rel not in ("results.jsonl", ".fairsub-batch.lock"):
            found[rel] = p.read_bytes()
    return found


def rows(out: pathlib.Path):
    return [json.loads(line) for line in (out / "results.jsonl").read_text().splitlines()]


def command_line(manifest, out):
    r = subprocess.run([cli_path(), "batch", str(manifest), "--out", str(out)], capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 1 and "2 of" in r.stderr, r.stderr  # the two bad jobs
    return files(out)


def check_rows(out, n):
    """One row per job, each output in one row only; the two bad jobs named."""
    rs = rows(out)
    assert len(rs) == n
    outputs = [r["output"] for r in rs]
    assert len(set(outputs)) == n
    bad = {r["output"]: r["error"] for r in rs if r["status"] == "error"}
    assert set(bad) == {"bad/c.obj", "bad/big.obj"}
    assert "corrupt.obj:3: face refers to vertex 7" in bad["bad/c.obj"]
    assert "too large" in bad["bad/big.obj"]
    measured = [r for r in rs if r["output"].endswith(".bv")]
    assert measured and all(r["metrics"]["check"]["continuity"]["patches"] == r["counts"]["patches"]
                            for r in measured)
    return rs


def test_without_a_client_the_files_are_the_command_lines(tmp_path):
    manifest, n = make_manifest(tmp_path)
    want = command_line(manifest, tmp_path / "cli")
    summary = fairsub.batch.run(manifest, tmp_path / "py", jobs=2)
    assert (summary["ok"], summary["error"], summary["skipped"]) == (n - 2, 2, 0)
    assert files(tmp_path / "py") == want
    check_rows(tmp_path / "py", n)
    again = fairsub.batch.run(manifest, tmp_path / "py", jobs=2)
    assert (again["ok"], again["error"], again["skipped"]) == (0, 2, n - 2)


# The longest the Dask run may take (it takes about 20 s on 2 busy cores).
DASK_SECONDS = 300


def dask_or_skip():
    if os.environ.get("FAIRSUB_REQUIRE_DASK") == "1":
        import distributed  # noqa: F401  (required: fail here when missing)
    return pytest.importorskip("distributed")


def test_dask_cluster_with_a_worker_killed_gives_the_same_files(tmp_path):
    distributed = dask_or_skip()
    manifest, n = make_manifest(tmp_path, heavy=24)
    want = command_line(manifest, tmp_path / "cli")
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
    client = distributed.Client(cluster)
    killed = {}

    def on_row(row):
        # once some results are in, kill a worker process that has tasks (by SIGKILL: its
        # tasks are lost and the scheduler runs them again elsewhere)
        if killed or row["status"] == "skipped" or sum(1 for _ in seen) < 10:
            seen.append(row)
            return
        processing = {w: ks for w, ks in client.processing().items() if ks}
        if not processing:
            return
        worker = sorted(processing)[0]
        pid = client.run(os.getpid, workers=[worker])[worker]
        os.kill(pid, signal.SIGKILL)
        killed[worker] = list(processing[worker])

    def too_long(signum, frame):
        raise TimeoutError("the Dask run took over %d s" % DASK_SECONDS)

    seen = []
    # bounded in time: a run that hangs (a task never retried) fails instead of stalling CI
    previous = signal.signal(signal.SIGALRM, too_long)
    signal.alarm(DASK_SECONDS)
    try:
        summary = fairsub.batch.run(manifest, tmp_path / "dask", client=client, on_row=on_row)
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)
        client.close()
        cluster.close()
    assert killed, "no worker was killed: the run ended too early"
    assert (summary["ok"], summary["error"]) == (n - 2, 2)
    assert files(tmp_path / "dask") == want
    rs = check_rows(tmp_path / "dask", n)
    lost = [k for ks in killed.values() for k in ks]
    done = {"fairsub-batch-%d-%s" % (r["line"], os.path.basename(r["output"])): r["status"] for r in rs}
    assert lost and all(k in done for k in lost)
