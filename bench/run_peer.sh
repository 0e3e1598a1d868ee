#!/usr/bin/env bash
# fairsub against OpenSubdiv 3.5 (Debian's libosd-dev), on the same generated meshes, in one go.
#
#   bench/run_peer.sh            # from the repository root; results in target/peer/
#
# Installs libosd-dev and g++ when missing (apt-get, through sudo unless run as root), builds the
# C++ peer (bench/osd_peer.cpp) and fairsub (release), generates closed tori, then measures:
#
#   1. whole process, OBJ in -> binary PLY out (fsync'ed, renamed into place on both sides):
#      Catmull-Clark, 100k quads, level 3 (and Loop, 100k triangles, level 3): best wall time of
#      REPS runs (the programs take turns), peak RSS (/usr/bin/time), output bytes; the outputs are checked to be the same
#      mesh (same faces, points within 1e-9 of the bounding box diagonal).
#      The same for a creased torus (Catmull-Clark; crease and corner tags, infinitely sharp and
#      semi-sharp 0.5 .. 4, `fairsub-bench gen creased-quad-torus`).
#      fairsub uses all cores (RAYON_NUM_THREADS unset) and is also run on one thread; the
#      OpenSubdiv Far refiner is single-threaded.
#   2. stencil re-application (animation: same topology, new points): the factorized table from
#      the control points of a 10k-quad torus to its level 3, applied once per run, best of
#      STENCIL_REPS: OpenSubdiv's Osd::CpuEvaluator (one thread, float) against fairsub's
#      StencilTable::apply_into and PackedStencilTable::apply_into (one thread, then two; double).
#   3. an EG cap against a Catmull-Clark cap with the same rings (8 + fill) at valences 3 and 5.
#
# Environment: REPS (default 3), STENCIL_REPS (20), FACES (100k), LEVELS (3), STENCIL_FACES (10k),
# OUT (target/peer), TABLE (unset: also write the table as Markdown with its generated header,
# bench/table.sh; the guide's is written by
#   TABLE=docs/guide/src/tables/opensubdiv-refinement.md bench/run_peer.sh
# ). Not part of CI: it needs a C++ toolchain and OpenSubdiv, and takes about a minute on two
# cores.
set -euo pipefail

. "$(dirname "$0")/table.sh"
cd "$(dirname "$0")/.."
REPS=${REPS:-3}
STENCIL_REPS=${STENCIL_REPS:-20}
FACES=${FACES:-100k}
LEVELS=${LEVELS:-3}
STENCIL_FACES=${STENCIL_FACES:-10k}
OUT=${OUT:-target/peer}
mkdir -p "$OUT"

# --- install and build ------------------------------------------------------------------------
need=()
dpkg -s libosd-dev >/dev/null 2>&1 || need+=(libosd-dev)
command -v g++ >/dev/null 2>&1 || need+=(g++)
[ -x /usr/bin/time ] || need+=(time)
if [ ${#need[@]} -gt 0 ]; then
    echo "installing ${need[*]}"
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo=sudo
    $sudo apt-get update
    $sudo apt-get install -y --no-install-recommends "${need[@]}"
fi
g++ -O3 -std=c++17 -o "$OUT/osd_peer" bench/osd_peer.cpp -losdCPU
cargo build --release --quiet --bin fairsub --example fairsub-bench
FAIRSUB=target/release/fairsub
TOOL=target/release/examples/fairsub-bench
PEER=$OUT/osd_peer

# --- meshes -----------------------------------------------------------------------------------
"$TOOL" gen quad-torus "$FACES" "$OUT/quads.obj"
"$TOOL" gen tri-torus "$FACES" "$OUT/tris.obj"
"$TOOL" gen creased-quad-torus "$FACES" "$OUT/creased.obj"
"$TOOL" gen quad-torus "$STENCIL_FACES" "$OUT/stencil.obj"

# Runs a command once; prints "wall_seconds peak_rss_bytes".
run_once() {
    local t0 t1 kb
    t0=$(date +%s%N)
    /usr/bin/time -f "%M" -o "$OUT/rss.txt" "$@" >/dev/null 2>&1
    t1=$(date +%s%N)
    kb=$(tail -n 1 "$OUT/rss.txt")
    awk -v a="$t0" -v b="$t1" -v kb="$kb" 'BEGIN { printf "%.3f %d\n", (b - a) / 1e9, kb * 1024 }'
}
min() { awk -v a="$1" -v b="$2" 'BEGIN { print (b == "" || a < b) ? a : b }'; }
max() { awk -v a="$1" -v b="$2" 'BEGIN { print (b == "" || a > b) ? a : b }'; }

ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }
mb() { awk -v a="$1" 'BEGIN { printf "%.0f MB", a / 1e6 }'; }

rows=()
md=()
row() {
    rows+=("$(printf '%-58s %14s %14s %8s' "$1" "$2" "$3" "$4")")
    md+=("| $1 | $2 | $3 | $4 |")
}

rm -f "$OUT"/compare-*.txt
echo "load before measuring: $(uptime)"
table_begin bench/run_peer.sh REPS STENCIL_REPS FACES LEVELS STENCIL_FACES

# --- 1. whole process ---------------------------------------------------------------------------
whole() { # scheme-name osd-scheme mesh label
    local key
    key=$(basename "$3" .obj)
    local fs_ply="$OUT/fairsub-$key.ply" osd_ply="$OUT/osd-$key.ply"
    local t_osd="" rss_osd="" t_fs="" rss_fs="" t_fs1="" t rss
    # The programs take turns, so a change of load on the machine hits both alike; best wall
    # time and largest peak RSS over REPS turns.
    for _ in $(seq "$REPS"); do
        read -r t rss < <(run_once "$PEER" refine "$2" "$3" "$LEVELS" "$osd_ply")
        t_osd=$(min "$t" "$t_osd")
        rss_osd=$(max "$rss" "$rss_osd")
        read -r t rss < <(run_once "$FAIRSUB" subdivide -s "$1" -l "$LEVELS" -o "$fs_ply" "$3")
        t_fs=$(min "$t" "$t_fs")
        rss_fs=$(max "$rss" "$rss_fs")
        read -r t _ < <(RAYON_NUM_THREADS=1 run_once "$FAIRSUB" subdivide -s "$1" -l "$LEVELS" \
            -o "$fs_ply" "$3")
        t_fs1=$(min "$t" "$t_fs1")
    done
    "$TOOL" compare "$fs_ply" "$osd_ply" >"$OUT/compare-$key.txt"
    local bytes dist
    bytes=$(stat -c %s "$fs_ply")
    dist=$(sed -n 's/^largest distance between matched points: \([^ ]*\).*/\1/p' "$OUT/compare-$key.txt")
    same+=("$4: identical faces, points within $dist")
    row "$4: wall s (all cores)" "$t_osd" "$t_fs" "$(ratio "$t_osd" "$t_fs")x"
    row "$4: wall s (fairsub on 1 thread)" "$t_osd" "$t_fs1" "$(ratio "$t_osd" "$t_fs1")x"
    row "$4: peak RSS / output ($(mb "$bytes"))" "$(ratio "$rss_osd" "$bytes")" \
        "$(ratio "$rss_fs" "$bytes")" "$(ratio "$rss_osd" "$rss_fs")x"
}
same=()
whole catmull-clark catmark "$OUT/quads.obj" "CC $FACES quads L$LEVELS"
whole loop loop "$OUT/tris.obj" "Loop $FACES tris L$LEVELS"
whole catmull-clark catmark "$OUT/creased.obj" "CC $FACES quads, creased, L$LEVELS"

# --- 2. stencil re-application ------------------------------------------------------------------
osd_st=$("$PEER" stencils catmark "$OUT/stencil.obj" 3 "$STENCIL_REPS")
fs_st=$("$TOOL" reapply "$OUT/stencil.obj" catmull-clark 3 "$STENCIL_REPS")
echo "$osd_st" >"$OUT/stencils-osd.txt"
echo "$fs_st" >"$OUT/stencils-fairsub.txt"
num() { sed -n "s/.*$1 apply 1 thread: \([0-9.]*\) ms.*2 threads: \([0-9.]*\) ms.*/\\$2/p" <<<"$fs_st"; }
osd1=$(sed -n 's/.*apply 1 thread: \([0-9.]*\) ms.*/\1/p' <<<"$osd_st")
fs1=$(num table 1)
fs2=$(num table 2)
pk1=$(num packed 1)
pk2=$(num packed 2)
row "stencils CC $STENCIL_FACES -> L3: ms, 1 thread, table" "$osd1" "$fs1" "$(ratio "$osd1" "$fs1")x"
row "stencils CC $STENCIL_FACES -> L3: ms, 1 thread, packed" "$osd1" "$pk1" "$(ratio "$osd1" "$pk1")x"
row "stencils: fairsub 2 threads table (ratio: vs 1 thread)" "-" "$fs2" "$(ratio "$fs1" "$fs2")x"
row "stencils: fairsub 2 threads packed (ratio: vs 1 thread)" "-" "$pk2" "$(ratio "$pk1" "$pk2")x"

# --- 3. caps (fairsub only: OpenSubdiv has no EG) --------------------------------------------
caps=()
for n in 3 5; do
    caps+=("$("$TOOL" caps "$n" 8 "$STENCIL_REPS")")
done

echo "load after measuring: $(uptime)"
echo
printf '%-58s %14s %14s %8s\n' "measure" "OpenSubdiv" "fairsub" "ratio"
printf '%s\n' "${rows[@]}"
echo
echo "ratio: OpenSubdiv / fairsub (above 1: fairsub is faster or leaner); outputs checked equal:"
grep -h "largest distance\|faces:" "$OUT"/compare-*.txt
echo
echo "EG cap against Catmull-Clark cap, same rings (whole c-net surfaces, best of $STENCIL_REPS):"
printf '%s\n' "${caps[@]}"

# --- the Markdown table (TABLE) -----------------------------------------------------------------
{
    echo "| measure (best of REPS; ratio OpenSubdiv / fairsub) | OpenSubdiv 3.5 | fairsub | ratio |"
    echo "| --- | --- | --- | --- |"
    printf '%s\n' "${md[@]}"
    for c in "${caps[@]}"; do
        # "valence N, R rings + fill: EG A ms (P patches), Catmull-Clark B ms (Q patches), EG / CC = X"
        sed -n 's/^valence \([0-9]*\), \([0-9]*\) rings + fill: EG \([0-9.]*\) ms.*Catmull-Clark \([0-9.]*\) ms.*EG \/ CC = \([0-9.]*\)$/| EG cap against Catmull-Clark cap, valence \1, \2 rings + fill: ms (ratio: EG \/ CC) | - | EG \3, CC \4 | \5 |/p' <<<"$c"
    done
    echo
    echo "Outputs checked the same mesh: $(IFS=';'; echo "${same[*]}" | sed 's/;/; /g')."
} | table_write
