#!/usr/bin/env bash
# fairsub's patch tables against OpenSubdiv 3.5's adaptive patch tables (Debian's libosd-dev).
#
#   bench/run_patch_peer.sh          # from the repository root; results in target/patch-peer/
#
# Installs libosd-dev and g++ when missing (tests/peer/build.sh), builds the C++ peer (bench/osd_peer.cpp, mode
# `patches`) and fairsub-bench, generates two meshes of about 100k quads with extraordinary
# vertices, and on each measures (best of REPS):
#
#   - building the Catmull-Clark patch table: OpenSubdiv's TopologyRefiner + RefineAdaptive
#     (isolation ISOLATION) + PatchTableFactory (Gregory end caps, double) + StencilTable to
#     the refined and local points + PatchMap; fairsub's complex (RINGS rings and G^1 caps) +
#     patch stencil table + evaluation index;
#   - re-applying the table to the control points;
#   - evaluating POINTS points (per face a k x k grid; point, first and second derivatives):
#     PatchMap::FindPatch + PatchTable::EvaluateBasis against Surface::evaluate_many and
#     Surface::evaluate_into (a buffer allocated once);
#   - and compares the evaluated points (the two surfaces agree on regular faces; near the
#     extraordinary vertices OpenSubdiv's Gregory end caps and fairsub's rings + G^1 caps are
#     different approximations of the limit surface).
#
# Meshes: `cube7` (the cube refined 7 times: 98,304 quads, 8 extraordinary vertices) and
# `quad-evs` (a triangle torus refined twice: 100k quads, an extraordinary vertex of valence 3
# or 6 in every 2 x 2 block). Environment: REPS (2), RINGS (4), ISOLATION (4), POINTS (1000000),
# OUT (target/patch-peer), TABLE (unset: also write the table as Markdown with its generated
# header, bench/table.sh; the guide's is written by
#   TABLE=docs/guide/src/tables/patch-tables-opensubdiv.md bench/run_patch_peer.sh
# ). OpenSubdiv runs on one thread, fairsub on all cores and on one.
set -euo pipefail

. "$(dirname "$0")/table.sh"
cd "$(dirname "$0")/.."
REPS=${REPS:-2}
RINGS=${RINGS:-4}
ISOLATION=${ISOLATION:-4}
POINTS=${POINTS:-1000000}
OUT=${OUT:-target/patch-peer}
mkdir -p "$OUT"

# libosd-dev and g++ (installed when missing, as for the tests' peer)
tests/peer/build.sh >/dev/null
g++ -O3 -std=c++17 -o "$OUT/osd_peer" bench/osd_peer.cpp -losdCPU
cargo build --release --quiet --bin fairsub --example fairsub-bench
FAIRSUB=target/release/fairsub
TOOL=target/release/examples/fairsub-bench

"$FAIRSUB" subdivide gallery:cube --scheme catmull-clark --levels 7 -o "$OUT/cube7.obj"
"$TOOL" gen quad-evs 100k "$OUT/quad-evs.obj"

echo "load before measuring: $(uptime)"
table_begin bench/run_patch_peer.sh REPS RINGS ISOLATION POINTS
md=()
for mesh in cube7 quad-evs; do
    echo "== $mesh =="
    "$OUT/osd_peer" patches "$OUT/$mesh.obj" "$ISOLATION" "$POINTS" "$REPS" "$OUT/$mesh.osd.bin" \
        | tee "$OUT/$mesh.osd.txt"
    "$TOOL" patch-table "$OUT/$mesh.obj" "$RINGS" "$POINTS" "$REPS" "$OUT/$mesh.fairsub.bin" \
        | tee "$OUT/$mesh.fairsub.txt"
    echo "-- fairsub on one thread"
    RAYON_NUM_THREADS=1 "$TOOL" patch-table "$OUT/$mesh.obj" "$RINGS" "$POINTS" 1 \
        "$OUT/$mesh.fairsub1.bin" | tee "$OUT/$mesh.fairsub1.txt"
    "$TOOL" compare-points "$OUT/$mesh.osd.bin" "$OUT/$mesh.fairsub.bin" \
        | tee "$OUT/$mesh.compare.txt"

    # The Markdown rows, read off the three programs' lines (printed above).
    get() { sed -n "s/$2/\\1/p" "$OUT/$mesh.$1.txt" | sed -n 1p; }
    faces=$(sed -n 's/^opensubdiv adaptive catmark, \([0-9]*\) faces.*/\1/p' "$OUT/$mesh.osd.txt")
    o_build=$(get osd '^build .*: \([0-9.]*\) ms$')
    o_apply=$(get osd '^re-apply the stencils to the control points: \([0-9.]*\) ms$')
    o_eval=$(get osd '^evaluate [0-9]* points (point, d1, d2): \([0-9.]*\) ms;.*')
    for f in fairsub fairsub1; do
        b=$(get $f '^build: .* = \([0-9.]*\) ms .*')
        i=$(get $f '^build: .*evaluation index \([0-9.]*\) ms = .*')
        a=$(get $f '^re-apply the table to the control points: \([0-9.]*\) ms;.*')
        ai=$(get $f '^re-apply .*storage reused): \([0-9.]*\) ms$')
        e=$(get $f '^evaluate .*evaluate_into a reused buffer: \([0-9.]*\) ms$')
        em=$(get $f '^evaluate [0-9]* points (point, d1, d2, normal, curvature): \([0-9.]*\) ms .*')
        printf -v "${f}_b" %s "$b"
        printf -v "${f}_i" %s "$i"
        printf -v "${f}_a" %s "$a / $ai"
        printf -v "${f}_e" %s "$e"
        printf -v "${f}_em" %s "$em"
    done
    q() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2fx", a / b }'; }
    worst=$(sed -n 's/.*largest distance \(.*\)$/\1/p' "$OUT/$mesh.compare.txt")
    md+=("| $mesh ($faces quads) | build (complex, table, evaluation index) | $o_build | $fairsub_b | $fairsub1_b | $(q "$fairsub_b" "$o_build") |")
    md+=("| | of which the evaluation index | | $fairsub_i | $fairsub1_i | |")
    md+=("| | re-apply: OpenSubdiv's stencils; fairsub's \`apply\` / \`apply_into\` | $o_apply | $fairsub_a | $fairsub1_a | |")
    md+=("| | evaluate $POINTS points: \`evaluate_into\` (\`evaluate_many\`) | $o_eval | $fairsub_e ($fairsub_em) | $fairsub1_e ($fairsub1_em) | $(q "$fairsub_e" "$o_eval") |")
    md+=("| | largest distance between the evaluated points | $worst | | | |")
done
echo "load after measuring: $(uptime)"
{
    echo "| mesh | measure (ms, best of REPS; one run on one thread) | OpenSubdiv 3.5 (1 thread) | fairsub ($(nproc) threads) | fairsub (1 thread) | fairsub / OpenSubdiv |"
    echo "| --- | --- | --- | --- | --- | --- |"
    printf '%s\n' "${md[@]}"
} | table_write
