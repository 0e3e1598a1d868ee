#!/usr/bin/env bash
# Issue 17's evaluation target end to end: `fairsub eval` of 10^6 points of a 10k-face net in at
# most 1 s, the whole process (reading the net and the points file, building the surface,
# locating, evaluating, printing every number exactly).
#
#   bench/run_eval_cli.sh            # from the repository root; files in target/eval-cli/
#
# The net is `fairsub-bench gen quad-evs 10k` (9,984 quads, a vertex of valence 3 or 6 in
# every 2 x 2 block: 1,248 extraordinary vertices), the points POINTS random `F:U:V` lines
# (Python's `random`, seed 7), the output goes to a file. Prints the best, median and worst
# wall time of REPS runs for `--rings RINGS` (text, and `--binary` records) and for the limit surface (no `--rings`), and the same with
# `RAYON_NUM_THREADS=1`. Environment: REPS (3), RINGS (4), POINTS (1000000),
# OUT (target/eval-cli), TABLE (unset: also write the table as Markdown with its generated
# header, bench/table.sh; the guide's is written by
#   TABLE=docs/guide/src/tables/eval-cli.md bench/run_eval_cli.sh
# ).
set -euo pipefail

. "$(dirname "$0")/table.sh"
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

# Wall times of REPS runs of "$@" (stdout to a fresh file), as "BEST MEDIAN WORST" seconds.
# Before each run the previous output is removed and the page cache written back (`sync`,
# outside the timing): otherwise the kernel's flusher writes the previous run's 281 MB while
# this one runs (ext4 starts that writeback when a truncated file is closed) and the series
# measures the runs before it. A single run on an idle machine has nothing of the kind.
walls() {
    local all=""
    for _ in $(seq "$REPS"); do
        rm -f "$OUT/out.txt"
        sync
        sleep 0.2
        local s e
        s=$(date +%s.%N)
        "$@" >"$OUT/out.txt" 2>/dev/null
        e=$(date +%s.%N)
        all="$all $(python3 -c "print($e - $s)")"
    done
    python3 -c "import statistics as st, sys; t = sorted(map(float, sys.argv[1:])); print(f'{t[0]:.3f} {st.median(t):.3f} {t[-1]:.3f}')" $all
}

md=()
# case LABEL MARKDOWN-LABEL COMMAND...: times the command, prints its line and keeps its row
case_() {
    local label=$1 mdlabel=$2 b m w
    shift 2
    read -r b m w < <(walls "$@")
    echo "  $label best $b s, median $m s, worst $w s"
    md+=("| $mdlabel | $b | $m | $w |")
}

table_begin bench/run_eval_cli.sh REPS RINGS POINTS
faces=$(grep -c '^f ' "$OUT/net.obj")
echo "fairsub eval, $POINTS points of $faces faces (load: $(cut -d' ' -f1-3 /proc/loadavg))"
case_ "--rings $RINGS:          " "text, \`--rings $RINGS\`" \
    "$FAIRSUB" eval "$OUT/net.obj" --scheme catmull-clark --rings "$RINGS" --at-file "$OUT/points.txt"
bytes=$(wc -c <"$OUT/out.txt")
echo "  (output: $bytes bytes)"
case_ "--rings $RINGS --binary:" "\`--rings $RINGS --binary\`" \
    "$FAIRSUB" eval "$OUT/net.obj" --scheme catmull-clark --rings "$RINGS" --binary --at-file "$OUT/points.txt"
RAYON_NUM_THREADS=1 case_ "--rings $RINGS, 1 thread:" "text, \`--rings $RINGS\`, one thread" \
    "$FAIRSUB" eval "$OUT/net.obj" --scheme catmull-clark --rings "$RINGS" --at-file "$OUT/points.txt"
case_ "limit surface:       " "text, the limit surface (no \`--rings\`)" \
    "$FAIRSUB" eval "$OUT/net.obj" --scheme catmull-clark --at-file "$OUT/points.txt"
case_ "build only (1 point, --rings $RINGS):" "the surface alone (1 point, \`--rings $RINGS\`)" \
    "$FAIRSUB" eval "$OUT/net.obj" --scheme catmull-clark --rings "$RINGS" --at 0:0.5:0.5
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
{
    echo "| \`fairsub eval\`, $POINTS random points of quad-evs ($faces quads), whole process | best (s) | median (s) | worst (s) |"
    echo "| --- | --- | --- | --- |"
    printf '%s\n' "${md[@]}"
    echo
    echo "Text output of the random points: $bytes bytes; REPS runs of each case."
} | table_write
