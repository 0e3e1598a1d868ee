#!/usr/bin/env bash
# Regenerates the non-box pictures of the README (deterministic output): the cube and
# tetrahedron of the paper's Fig. 11 beside Doo-Sabin, Loop and Catmull-Clark, and the FCV-scale
# series of its Fig. 10 (FCVs = 0.5, 1, 1.5 times the face barycentres of a cube centred at the
# origin; the gallery nets nonbox-cube-fcv-S are those nets triangulated around their FCVs, so
# the control net drawn over the surface shows the FCVs as the centres of the triangle fans).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
F=target/release/fairsub
common=(--rings 4 --size 200x200 --elevation 30 --modes highlight,mean)
$F compare gallery:cube --schemes nonbox,doo-sabin,catmull-clark "${common[@]}" -o docs/images/nonbox-cube.png
$F compare gallery:tetrahedron --schemes nonbox,doo-sabin,loop,catmull-clark "${common[@]}" -o docs/images/nonbox-tetrahedron.png
for s in 0.5 1 1.5; do
  $F compare gallery:nonbox-cube-fcv-$s --schemes nonbox-4dir --modes shaded,highlight,mean \
    --rings 4 --size 200x200 --elevation 30 --distance 7 --range 2.5 --overlay net \
    -o docs/images/nonbox-cube-fcv-$s.png
done
# The open pipe of Fig. 9: boundary V- and E-vertices by the cubic B-spline rules, the boundary
# NFCV rule is fairsub's reconstruction (ghost FCVs).
$F compare gallery:open-pipe --schemes nonbox,catmull-clark "${common[@]}" -o docs/images/nonbox-open-pipe.png
