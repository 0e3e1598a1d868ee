#!/usr/bin/env bash
# Issue 17's evaluation target end to end: `fairsub eval` of 10^6 points of a 10k-face net in at
# most 1 s, the whole process (reading the net and the points file, building the surface,
# locating, evaluating, printing every number exactly).
#
#   bench/run_eval_cli.sh            # from the repository root; files in target/eval-cli/
#
# The net is `fairsub-bench gen quad-evs 10k` (9,984 quads, a vertex of valence 3 or 6 in
# every 2 x 2 block: 1,248 extraordinary vertices), the points POINTS random `F:U:V` lines
# (Python's `random`, seed 7), the output goes to a file. Prints the best wall time of REPS
# runs for `--rings RINGS` (text, and `--binary` records) and for the limit surface (no `--rings`), and the same with
# `RAYON_NUM_THREADS=1`. Environment: REPS (3), RINGS (4), POINTS (1000000),
# OUT (target/eval-cli).
set -euo pipefail

cd "$(dirname "$0")/.."
REPS=${REPS:-3}
RINGS=${RINGS:-4}
POINTS=${POINTS:-1000000}
OUT=${OUT:-target/eval-cli}
mkdir -p "$OUT"
cargo build --release --quiet --bin fairsub --example fairsub-bench
FAIRSUB=target/release/fairsub
"target/release/examples/fairsub-bench" gen quad-evs 10k "$OUT/net.obj" >/dev/null
python3 - "$OUT/net.obj" "$OUT/points.txt" "$POINTS" <<'PY'
import random, sys
net, out, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
faces = sum(1 for line in open(net) if line.startswith("f "))
random.seed(7)
with open(out, "w") as f:
    for _ in range(n):
        f.write(f"{random.randrange(faces)}:{random.random()}:{random.random()}\n")
PY

best() { # best wall time in seconds of REPS runs of "$@" (stdout to a file)
    local b=""
    for _ in $(seq "$REPS"); do
        local s e
        s=$(date +%s.%N)
        "$@" >"$OUT/out.txt" 2>/dev/null
        e=$(date +%s.%N)
        b=$(python3 -c "import sys; t=$e-$s; b='$b'; print(t if not b else min(t, float(b)))")
    done
    printf '%.3f s' "$b"
}

echo "fairsub eval, $POINTS points of $(grep -c '^f ' "$OUT/net.obj") faces (load: $(cut -d' ' -f1-3 /proc/loadavg))"
echo "  --rings $RINGS:          $(best "$FAIRSUB" eval "$OUT/net.obj" --scheme catmull-clark --rings "$RINGS" --at-file "$OUT/points.txt")"
echo "  (output: $(wc -c <"$OUT/out.txt") bytes)"
echo "  --rings $RINGS --binary: $(best "$FAIRSUB" eval "$OUT/net.obj" --scheme catmull-clark --rings "$RINGS" --binary --at-file "$OUT/points.txt")"
echo "  --rings $RINGS, 1 thread: $(RAYON_NUM_THREADS=1 best "$FAIRSUB" eval "$OUT/net.obj" --scheme catmull-clark --rings "$RINGS" --at-file "$OUT/points.txt")"
echo "  limit surface:       $(best "$FAIRSUB" eval "$OUT/net.obj" --scheme catmull-clark --at-file "$OUT/points.txt")"
echo "  build only (1 point, --rings $RINGS): $(best "$FAIRSUB" eval "$OUT/net.obj" --scheme catmull-clark --rings "$RINGS" --at 0:0.5:0.5)"
