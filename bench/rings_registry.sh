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
# build), SHAPES ("convex"), SCHEMES (default: all patch-writing schemes), SCHEME_VALENCES
# (restricts a slow scheme to some valences: "guided-bi3-macro=3,5" runs it at valences 3 and 5
# only; the others print `not run`), LIMIT (3), OUT (target/rings-registry), TABLE (unset: also
# write the table as Markdown with its generated header, bench/table.sh: one row per scheme,
# one column per net; the guide's is written by
#   TABLE=docs/guide/src/tables/rings-registry.md bench/rings_registry.sh
# ). The machine's load (`uptime`) is printed first and last: the ratios are measured in one
# run, so they are comparable under the same load.
set -euo pipefail

. "$(dirname "$0")/table.sh"
cd "$(dirname "$0")/.."
knobs=(RINGS REPS VALENCES SHAPES SCHEME_VALENCES LIMIT)
[ -z "${SCHEMES:-}" ] || knobs+=(SCHEMES)
[ -z "${FAIRSUB:-}" ] || knobs+=(FAIRSUB)
RINGS=${RINGS:-3}
REPS=${REPS:-1}
VALENCES=${VALENCES:-"3 5 6 7 8 9 10"}
SHAPES=${SHAPES:-convex}
LIMIT=${LIMIT:-3}
SCHEME_VALENCES=${SCHEME_VALENCES:-}
OUT=${OUT:-target/rings-registry}
FAIRSUB=${FAIRSUB:-target/release/fairsub}
mkdir -p "$OUT"
# the default binary is brought up to date (a no-op when it is), so it is the commit's
[ "$FAIRSUB" != target/release/fairsub ] || cargo build --release --quiet -p fairsub --bin fairsub

if [ -z "${SCHEMES:-}" ]; then
    SCHEMES=$("$FAIRSUB" schemes 2>/dev/null | awk '
        /^[^ ]/ { name = $1 }
        /^ +commands:/ && /--rings/ { print name }')
fi

echo "load before: $(uptime)"
table_begin bench/rings_registry.sh "${knobs[@]}"
# results.tsv: scheme, net, then "refused", "not run" or the time and memory ratios
: >"$OUT/results.tsv"

# skipped SCHEME VALENCE: true when SCHEME_VALENCES restricts SCHEME to other valences
skipped() {
    local e
    for e in $SCHEME_VALENCES; do
        if [ "${e%%=*}" = "$1" ]; then
            case ",${e#*=}," in *",$2,"*) return 1 ;; *) return 0 ;; esac
        fi
    done
    return 1
}
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
        printf '%s\t%s\t%s s, %.0f MB\n' guided-bi5 "$net" "$ref_t" "$(awk -v k="$ref_kb" 'BEGIN { print k / 1024 }')" >>"$OUT/results.tsv"
        for s in $SCHEMES; do
            if [ "$s" = guided-bi5 ]; then
                r="$ref_t $ref_kb"
            elif skipped "$s" "$v"; then
                printf '%-18s %-16s not run (SCHEME_VALENCES)\n' "$s" "$net"
                printf '%s\t%s\tnot run\n' "$s" "$net" >>"$OUT/results.tsv"
                continue
            else
                r=$(run "$s" "$net")
            fi
            if [ "${r%% *}" = refused ]; then
                printf '%-18s %-16s %s\n' "$s" "$net" "$r"
                printf '%s\t%s\trefused\n' "$s" "$net" >>"$OUT/results.tsv"
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
            if [ "$s" != guided-bi5 ]; then
                awk -v s="$s" -v net="$net" -v t="$t" -v kb="$kb" -v rt="$ref_t" -v rkb="$ref_kb" \
                    -v lim="$LIMIT" 'BEGIN {
                    tt = (t < 0.01 ? 0.01 : t); rr = (rt < 0.01 ? 0.01 : rt)
                    q = tt / rr; qm = kb / rkb
                    a = sprintf("%.1fx", q); b = sprintf("%.1fx", qm)
                    if (q > lim) a = "**" a "**"
                    if (qm > lim) b = "**" b "**"
                    printf "%s\t%s\t%s / %s\n", s, net, a, b
                }' >>"$OUT/results.tsv"
            fi
        done
    done
done
echo "flagged runs (time or memory above ${LIMIT}x guided-bi5): $flagged"
echo "load after: $(uptime)"
# The Markdown table: a row per scheme (guided-bi5 first, in seconds and MB), a column per net.
awk -F'\t' -v lim="$LIMIT" -v rings="$RINGS" '
    !($2 in seen) { seen[$2] = 1; nets[++nn] = $2 }
    !($1 in known) { known[$1] = 1; schemes[++ns] = $1 }
    { cell[$1, $2] = $3 }
    END {
        printf "| scheme (`--rings %s`): time / peak RSS against guided-bi5 |", rings
        for (j = 1; j <= nn; j++) printf " %s |", nets[j]
        printf "\n| --- |"
        for (j = 1; j <= nn; j++) printf " --- |"
        printf "\n"
        for (i = 1; i <= ns; i++) {
            printf "| %s |", schemes[i]
            for (j = 1; j <= nn; j++) printf " %s |", ((schemes[i], nets[j]) in cell ? cell[schemes[i], nets[j]] : "")
            printf "\n"
        }
        printf "\nThe guided-bi5 row is its wall time and peak RSS; the others are ratios to it on the same net, bold above %sx; `refused`: the scheme does not take the net.\n", lim
    }' "$OUT/results.tsv" | table_write
rm -f "$OUT/out.bv" "$OUT/time" "$OUT/err"
