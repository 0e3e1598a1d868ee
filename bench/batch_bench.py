"""Benchmark of `fairsub batch` (issue 50): 1,000 small nets (gallery nets and generated grids)
through `fairsub batch`, through a shell loop of single-file `fairsub subdivide` calls, and
through `fairsub.batch.run` on a Dask LocalCluster of 2 worker processes; prints meshes per
second and the ratios, with the machine's load.

    cargo build --release
    python bench/batch_bench.py [--jobs 1000] [--bin target/release/fairsub] [--no-dask]

Dask needs the package and `dask[distributed]` in the Python that runs this script. The
outputs of the three runs are compared byte for byte at the end.
"""

import argparse
import json
import os
import pathlib
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

REPO = pathlib.Path(__file__).resolve().parents[1]
GALLERY = ["cube", "tetrahedron", "octahedron", "icosahedron", "torus-evs", "open-grid", "prism-5",
           "cnet-3-saddle", "cnet-5-convex", "cnet-6-raised", "cnet-7-planar"]


def grid_obj(w, h, seed):
    lines = ["v %d %d %g" % (i, j, ((i * 7 + j * 3 + seed) % 11) / 10)
             for j in range(h + 1) for i in range(w + 1)]
    for j in range(h):
        for i in range(w):
            a = j * (w + 1) + i + 1
            lines.append("f %d %d %d %d" % (a, a + 1, a + w + 2, a + w + 1))
    return "\n".join(lines) + "\n"


def jobs(n, nets):
    """n small jobs: gallery nets under Catmull-Clark, Doo-Sabin and Loop-free schemes, and
    generated grids (levels 2 nets and rings 2 surfaces)."""
    out = []
    for k in range(n):
        if k % 2 == 0:
            g = GALLERY[(k // 2) % len(GALLERY)]
            scheme, ext = [("catmull-clark", "obj"), ("doo-sabin", "off"), ("pgs", "ply")][(k // 2) % 3]
            out.append({"input": "gallery:" + g, "scheme": scheme, "levels": 2, "output": "%d.%s" % (k, ext)})
        else:
            name = "grid%d.obj" % k
            (nets / name).write_text(grid_obj(2 + k % 4, 2 + k % 3, k))
            if k % 4 == 1:
                out.append({"input": "nets/" + name, "scheme": "catmull-clark", "levels": 2, "output": "%d.obj" % k})
            else:
                out.append({"input": "nets/" + name, "scheme": "catmull-clark", "rings": 2, "output": "%d.bv" % k})
    return out


def words(job, base, out):
    inp = job["input"] if job["input"].startswith("gallery:") else str(base / job["input"])
    how = ["--levels", str(job["levels"])] if "levels" in job else ["--rings", str(job["rings"])]
    return ["subdivide", inp, "--scheme", job["scheme"], *how, "-o", str(out / job["output"])]


def files(out):
    return {p.name: p.read_bytes() for p in out.iterdir()
            if p.is_file() and p.name not in ("results.jsonl", ".fairsub-batch.lock")}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--jobs", type=int, default=1000)
    ap.add_argument("--bin", default=str(REPO / "target" / "release" / "fairsub"))
    ap.add_argument("--no-dask", action="store_true")
    a = ap.parse_args()
    base = pathlib.Path(tempfile.mkdtemp(prefix="fairsub-batch-bench-"))
    (base / "nets").mkdir()
    js = jobs(a.jobs, base / "nets")
    manifest = base / "manifest.jsonl"
    manifest.write_text("".join(json.dumps(j) + "\n" for j in js))
    print("load before:", os.getloadavg())

    out = base / "batch"
    t = time.perf_counter()
    r = subprocess.run([a.bin, "batch", str(manifest), "--out", str(out)], capture_output=True, text=True)
    batch_s = time.perf_counter() - t
    assert r.returncode == 0, r.stderr

    loop_out = base / "loop"
    loop_out.mkdir()
    script = base / "loop.sh"
    script.write_text("set -e\n" + "".join(
        shlex.join([a.bin, *words(j, base, loop_out)]) + " 2>/dev/null\n" for j in js))
    t = time.perf_counter()
    subprocess.run(["bash", str(script)], check=True)
    loop_s = time.perf_counter() - t
    assert files(out) == files(loop_out), "batch and the shell loop wrote different files"

    print("%d meshes" % len(js))
    print("shell loop of fairsub subdivide: %7.2f s  %8.1f meshes/s" % (loop_s, len(js) / loop_s))
    print("fairsub batch (%d jobs at once): %7.2f s  %8.1f meshes/s  %5.1fx the shell loop"
          % (os.cpu_count(), batch_s, len(js) / batch_s, loop_s / batch_s))
    if not a.no_dask:
        from dask.distributed import Client, LocalCluster

        import fairsub.batch

        dask_out = base / "dask"
        with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster, \
                Client(cluster) as client:
            client.run(lambda: __import__("fairsub"))  # the package loaded before the clock starts
            t = time.perf_counter()
            s = fairsub.batch.run(manifest, dask_out, client=client)
            dask_s = time.perf_counter() - t
        assert s["ok"] == len(js), s
        assert files(dask_out) == files(out), "Dask and fairsub batch wrote different files"
        print("Dask LocalCluster, 2 workers:    %7.2f s  %8.1f meshes/s  %5.1fx the shell loop"
              % (dask_s, len(js) / dask_s, loop_s / dask_s))
    print("load after:", os.getloadavg())
    shutil.rmtree(base)


if __name__ == "__main__":
    sys.exit(main())
