#!/usr/bin/env bash
# Scaling benchmark of issue 20's once-quadratic cases: each case runs at a size n and at 10 n,
# best of REPS runs each, and the script prints the time ratio. A linear (or n log n) command
# gives a ratio near 10; the script exits non-zero when any ratio exceeds LIMIT (default 15).
#
#   bench/scaling.sh                 # REPS=3 LIMIT=15 BIN=target/release/fairsub OUT=target/scaling
#   CASES="info-kgon bv-groups" bench/scaling.sh
#
# Cases (small size -> large size):
#   info-kgon     `info` on one k-gon                                  20k -> 200k vertices
#   check-bv      `check` on a .bv grid of bi-3 patches                 10k -> 100k patches
#   bv-groups     `check` on a .bv with one `group` line per patch      10k -> 100k groups
#   fan-S         `subdivide --scheme S --rings 2` at one vertex of valence n 2k -> 20k
#                 (a disc of n quads; for loop a disc of 2n triangles), for every scheme S
#                 (FAN_SCHEMES); valence-fan is fan-catmull-clark
#   ds-kgon       `subdivide --scheme doo-sabin --levels 1` on a k-gon  20k -> 200k; a
#                 Doo-Sabin face point weighs every corner (k^2 stencil entries), so both
#                 are refused up front (`--max-memory 64M`): this measures reading and the
#                 estimate, which must not be quadratic
#   analyze-V     `analyze --scheme V --valence n`, n = 30 -> 300 (ANALYZE_N), for V in
#                 guided-bi5, pgs, nonbox: a dense eigen-decomposition up to 450 rows, the
#                 Fourier blocks of the block-circulant local matrix above
#                 (src/schemes/circulant.rs; guided's Bloch basis, src/schemes/guided/
#                 fourier.rs), linear in n. It starts at 30 because a run at valence 3 is 7 ms
#                 of process start (3 -> 30 measures the dense path near its bound: pgs x28,
#                 nonbox x50); measured 2026-12-03: pgs 30 -> 300 x1.2, nonbox x1.7,
#                 guided-bi5 x4.3 (analyze-guided-bi6, -bi4-macro, -bi3-macro also run:
#                 x4.6, x10.5, x7.5)
#
# Timings are wall-clock of the whole process (reading, work, writing) on whatever machine runs
# the script; run it on an idle machine. It is not part of `cargo test` (the project has no timed
# tests). TABLE (unset) also writes the table as Markdown with its generated header
# (bench/table.sh); the guide's is written by
#   TABLE=docs/guide/src/tables/scaling.md bench/scaling.sh
set -euo pipefail

. "$(dirname "$0")/table.sh"
cd "$(dirname "$0")/.."
knobs=(REPS LIMIT BIN ANALYZE_N)
[ -z "${FAN_SCHEMES:-}" ] || knobs+=(FAN_SCHEMES)
[ -z "${CASES:-}" ] || knobs+=(CASES)
REPS=${REPS:-3}
LIMIT=${LIMIT:-15}
BIN=${BIN:-target/release/fairsub}
OUT=${OUT:-target/scaling}
ANALYZE_N=${ANALYZE_N:-30}
FAN_SCHEMES=${FAN_SCHEMES:-"catmull-clark doo-sabin doo-sabin-cc loop nonbox nonbox-4dir eg qas-plus qas-plus-bi3 qas-0.4 qas-0.5-0.4 pgs pgs-dscc polar-bi2 tps tps-adjustable bi2-mixed guided-bi5 guided-bi6 guided-bi4-macro guided-bi3-macro"}
FANS=""
for s in $FAN_SCHEMES; do FANS="$FANS fan-$s"; done
CASES=${CASES:-"info-kgon check-bv bv-groups$FANS ds-kgon analyze-guided-bi5 analyze-pgs analyze-nonbox"}

# the default binary is brought up to date (a no-op when it is), so it is the commit's
if [ "$BIN" = target/release/fairsub ] || [ ! -x "$BIN" ]; then
    cargo build --release --quiet --bin fairsub >&2
fi
mkdir -p "$OUT"

# One k-gon (a disc of one face) in OBJ.
kgon() { # k file
    awk -v k="$1" 'BEGIN {
        for (i = 0; i < k; i++) { t = 6.283185307179586 * i / k; printf "v %.17g %.17g 0\n", cos(t), sin(t) }
        printf "f"; for (i = 1; i <= k; i++) printf " %d", i; printf "\n" }' >"$2"
}

# A disc of n quads around one vertex of valence n: centre 1, inner ring 2..n+1, outer ring
# n+2..2n+1; quad i is (centre, a_i, b_i, a_{i+1}).
fan() { # n file
    awk -v n="$1" 'BEGIN {
        print "v 0 0 0"
        for (i = 0; i < n; i++) { t = 6.283185307179586 * i / n; printf "v %.17g %.17g 0\n", cos(t), sin(t) }
        for (i = 0; i < n; i++) { t = 6.283185307179586 * (i + 0.5) / n; printf "v %.17g %.17g 0.1\n", 2 * cos(t), 2 * sin(t) }
        for (i = 0; i < n; i++) printf "f 1 %d %d %d\n", 2 + i, n + 2 + i, 2 + (i + 1) % n }' >"$2"
}

# A disc of 2n triangles around one vertex of valence n (Loop): centre 1, inner ring 2..n+1,
# outer ring n+2..2n+1; triangles (centre, a_i, a_{i+1}) and (a_i, b_i, a_{i+1}).
trifan() { # n file
    awk -v n="$1" 'BEGIN {
        print "v 0 0 0"
        for (i = 0; i < n; i++) { t = 6.283185307179586 * i / n; printf "v %.17g %.17g 0\n", cos(t), sin(t) }
        for (i = 0; i < n; i++) { t = 6.283185307179586 * (i + 0.5) / n; printf "v %.17g %.17g 0.1\n", 2 * cos(t), 2 * sin(t) }
        for (i = 0; i < n; i++) { printf "f 1 %d %d\n", 2 + i, 2 + (i + 1) % n; printf "f %d %d %d\n", 2 + i, n + 2 + i, 2 + (i + 1) % n } }' >"$2"
}

# A flat m x m grid of bi-3 patches in .bv (adjacent patches share their boundary rows); with
# groups=1 every patch gets its own `group` line.
bvgrid() { # m groups file
    awk -v m="$1" -v groups="$2" 'BEGIN {
        for (a = 0; a < m; a++) for (b = 0; b < m; b++) {
            if (groups) printf "group %d g%d\n", 1 + (a * m + b) % 16, a * m + b
            print "4 3"
            for (i = 0; i <= 3; i++) for (j = 0; j <= 3; j++) printf "%.17g %.17g 0\n", a + i / 3, b + j / 3
        } }' >"$3"
}

# Best of REPS wall-clock seconds of a command (its exit code must be $EXPECT, default 0).
best() {
    local bestt="" t s e code
    for _ in $(seq "$REPS"); do
        s=$(date +%s.%N)
        code=0
        "$@" >/dev/null 2>"$OUT/stderr" || code=$?
        if [ "$code" != "${EXPECT:-0}" ]; then
            echo "FAILED: $*" >&2
            cat "$OUT/stderr" >&2
            return 1
        fi
        e=$(date +%s.%N)
        t=$(echo "$e - $s" | bc -l)
        if [ -z "$bestt" ] || [ "$(echo "$t < $bestt" | bc -l)" = 1 ]; then bestt=$t; fi
    done
    printf '%.4f' "$bestt"
}

fail=0
md=()
table_begin bench/scaling.sh "${knobs[@]}"
printf '%-20s %10s %10s %10s %10s %7s\n' case n 10n "t(n) s" "t(10n) s" ratio
report() { # name n t1 t2 (an empty time: the command failed, reported by best)
    local ratio status=ok
    if [ -z "$3" ] || [ -z "$4" ]; then
        printf '%-20s %10s FAILED (command failed)\n' "$1" "$2"
        md+=("| \`$1\` | $2 | | | | command failed |")
        fail=1
        return
    fi
    ratio=$(echo "$4 / $3" | bc -l)
    if [ "$(echo "$ratio > $LIMIT" | bc -l)" = 1 ]; then status="FAIL (> $LIMIT)"; fail=1; fi
    printf '%-20s %10s %10s %10s %10s %7.2f %s\n' "$1" "$2" "$(($2 * 10))" "$3" "$4" "$ratio" "$status"
    md+=("$(printf '| `%s` | %s -> %s | %.3f | %.3f | %.1f | %s |' "$1" "$2" "$(($2 * 10))" "$3" "$4" "$ratio" "$status")")
}

for c in $CASES; do
    case $c in
    info-kgon)
        kgon 20000 "$OUT/k1.obj"; kgon 200000 "$OUT/k2.obj"
        report "$c" 20000 "$(best "$BIN" info "$OUT/k1.obj")" "$(best "$BIN" info "$OUT/k2.obj")"
        ;;
    check-bv)
        bvgrid 100 0 "$OUT/g1.bv"; bvgrid 316 0 "$OUT/g2.bv"
        report "$c" 10000 "$(best "$BIN" check "$OUT/g1.bv")" "$(best "$BIN" check "$OUT/g2.bv")"
        ;;
    bv-groups)
        bvgrid 100 1 "$OUT/h1.bv"; bvgrid 316 1 "$OUT/h2.bv"
        report "$c" 10000 "$(best "$BIN" check "$OUT/h1.bv")" "$(best "$BIN" check "$OUT/h2.bv")"
        ;;
    valence-fan | fan-*)
        s=${c#fan-}
        if [ "$c" = valence-fan ]; then s=catmull-clark; fi
        if [ "$s" = loop ]; then net=t; else net=f; fi
        if [ ! -f "$OUT/${net}2.obj" ]; then
            if [ $net = t ]; then trifan 2000 "$OUT/t1.obj"; trifan 20000 "$OUT/t2.obj"
            else fan 2000 "$OUT/f1.obj"; fan 20000 "$OUT/f2.obj"; fi
        fi
        report "$c" 2000 \
            "$(best "$BIN" subdivide "$OUT/${net}1.obj" --scheme "$s" --rings 2 -o "$OUT/${net}1.bv")" \
            "$(best "$BIN" subdivide "$OUT/${net}2.obj" --scheme "$s" --rings 2 -o "$OUT/${net}2.bv")"
        ;;
    ds-kgon)
        kgon 20000 "$OUT/d1.obj"; kgon 200000 "$OUT/d2.obj"
        report "$c" 20000 \
            "$(EXPECT=1 best "$BIN" --max-memory 64M subdivide "$OUT/d1.obj" --scheme doo-sabin --levels 1 -o "$OUT/d1.ply")" \
            "$(EXPECT=1 best "$BIN" --max-memory 64M subdivide "$OUT/d2.obj" --scheme doo-sabin --levels 1 -o "$OUT/d2.ply")"
        ;;
    analyze-*)
        s=${c#analyze-}
        n=$ANALYZE_N
        report "$c" "$n" "$(best "$BIN" analyze --scheme "$s" --valence "$n")" \
            "$(best "$BIN" analyze --scheme "$s" --valence "$((n * 10))")"
        ;;
    *)
        echo "unknown case $c" >&2
        exit 2
        ;;
    esac
done
{
    echo "| case | n -> 10 n | t(n) s | t(10 n) s | ratio | within $LIMIT |"
    echo "| --- | --- | --- | --- | --- | --- |"
    printf '%s\n' "${md[@]}"
} | table_write
exit $fail
