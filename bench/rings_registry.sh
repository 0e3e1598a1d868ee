#!/usr/bin/env bash
# `--rings` of every patch-writing scheme against guided-bi5 on the same net (issue 49).
#
#   bench/rings_registry.sh            # from the repository root; table on stdout
#
# The schemes are read from `fairsub schemes` (every scheme whose commands include
# `subdivide --rings`), so a new scheme is benchmarked without editing this script. Each runs
# `fairsub subdivide NET --scheme S --rings RINGS -o OUT.bv` on the gallery's c-nets
# `cnet-N-SHAPE` for N in VALENCES (best wall time of REPS runs, and the peak RSS of that run,
# both from `/usr/bin/time`), and the table prints each scheme's time and peak RSS with its
# ratio to guided-bi5's on the same net; a ratio above LIMIT is flagged `!`. A scheme that
# refuses a net (Loop takes triangles only) prints `refused` with the first line of its error.
#
# Environment: RINGS (3), REPS (1), VALENCES ("3 5 6 7 8 9 10": 4 is regular, no cap to
# build), SHAPES ("convex"), SCHEMES (default: all patch-writing schemes), LIMIT (3),
# OUT (target/rings-registry). The machine's load (`uptime`) is printed first and last: the
# ratios are measured in one run, so they are comparable under the same load.
set -euo pipefail

cd "$(dirname "$0")/.."
RINGS=${RINGS:-3}
REPS=${REPS:-1}
VALENCES=${VALENCES:-"3 5 6 7 8 9 10"}
SHAPES=${SHAPES:-convex}
LIMIT=${LIMIT:-3}
OUT=${OUT:-target/rings-registry}
FAIRSUB=${FAIRSUB:-target/release/fairsub}
mkdir -p "$OUT"
[ -x "$FAIRSUB" ] || cargo build --release --quiet -p fairsub --bin fairsub

if [ -z "${SCHEMES:-}" ]; then
    SCHEMES=$("$FAIRSUB" schemes 2>/dev/null | awk '
        /^[^ ]/ { name = $1 }
        /^ +commands:/ && /--rings/ { print name }')
fi

echo "load before: $(uptime)"
echo "rings $RINGS, best of $REPS; ratio = scheme / guided-bi5 on the same net; ! = above ${LIMIT}x"

# run SCHEME NET: prints "SECONDS KB" (best time of REPS, its peak RSS) or "refused MESSAGE"
run() {
    local scheme=$1 net=$2 best="" kb="" t m
    for _ in $(seq "$REPS"); do
        if ! /usr/bin/time -f "%e %M" -o "$OUT/time" "$FAIRSUB" subdivide "gallery/$net.obj" \
            --scheme "$scheme" --rings "$RINGS" -o "$OUT/out.bv" >/dev/null 2>"$OUT/err"; then
            echo "refused $(grep -v '^Command exited' "$OUT/err" | head -1 | cut -c1-60)"
            return
        fi
        read -r t m <"$OUT/time"
        if [ -z "$best" ] || awk "BEGIN { exit !($t < $best) }"; then
            best=$t
            kb=$m
        fi
    done
    echo "$best $kb"
}

printf '%-18s %-16s %8s %8s %9s %8s\n' scheme net seconds ratio "peak MB" ratio
flagged=0
for shape in $SHAPES; do
    for v in $VALENCES; do
        net="cnet-$v-$shape"
        [ -f "gallery/$net.obj" ] || continue
        read -r ref_t ref_kb < <(run guided-bi5 "$net")
        for s in $SCHEMES; do
            if [ "$s" = guided-bi5 ]; then
                r="$ref_t $ref_kb"
            else
                r=$(run "$s" "$net")
            fi
            if [ "${r%% *}" = refused ]; then
                printf '%-18s %-16s %s\n' "$s" "$net" "$r"
                continue
            fi
            read -r t kb <<<"$r"
            line=$(awk -v s="$s" -v net="$net" -v t="$t" -v kb="$kb" -v rt="$ref_t" \
                -v rkb="$ref_kb" -v lim="$LIMIT" 'BEGIN {
                    # /usr/bin/time prints hundredths: a 0.00 s run counts as 0.01 s
                    tt = (t < 0.01 ? 0.01 : t); rr = (rt < 0.01 ? 0.01 : rt)
                    q = tt / rr; qm = kb / rkb
                    printf "%-18s %-16s %8.2f %7.2fx%s %8.1f %7.2fx%s\n", s, net, t, q,
                        (q > lim ? "!" : " "), kb / 1024, qm, (qm > lim ? "!" : " ")
                }')
            echo "$line"
            case "$line" in *'!'*) flagged=$((flagged + 1)) ;; esac
        done
    done
done
echo "flagged runs (time or memory above ${LIMIT}x guided-bi5): $flagged"
echo "load after: $(uptime)"
rm -f "$OUT/out.bv" "$OUT/time" "$OUT/err"
