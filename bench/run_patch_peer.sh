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
# OUT (target/patch-peer). OpenSubdiv runs on one thread, fairsub on all cores and on one.
set -euo pipefail

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

for mesh in cube7 quad-evs; do
    echo "== $mesh =="
    "$OUT/osd_peer" patches "$OUT/$mesh.obj" "$ISOLATION" "$POINTS" "$REPS" "$OUT/$mesh.osd.bin"
    "$TOOL" patch-table "$OUT/$mesh.obj" "$RINGS" "$POINTS" "$REPS" "$OUT/$mesh.fairsub.bin"
    echo "-- fairsub on one thread"
    RAYON_NUM_THREADS=1 "$TOOL" patch-table "$OUT/$mesh.obj" "$RINGS" "$POINTS" 1 \
        "$OUT/$mesh.fairsub1.bin"
    "$TOOL" compare-points "$OUT/$mesh.osd.bin" "$OUT/$mesh.fairsub.bin"
done
