#!/usr/bin/env bash
# Regenerates the pictures of the guide's page on sqrt(3) and the modified butterfly scheme:
# highlight lines on the icosahedron refined by Loop, sqrt(3) and butterfly to about the same
# number of triangles (5,120, 4,860, 5,120). These two schemes write no exact patches, so the
# refined net is drawn with interpolated normals (render --levels) and the curvature modes,
# which need patches, are not available for them.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
F=target/release/fairsub
$F render gallery:icosahedron -s loop --levels 4 -m highlight --size 240x240 -o docs/images/tri-loop-icosahedron.png
$F render gallery:icosahedron -s sqrt3 --levels 5 -m highlight --size 240x240 -o docs/images/tri-sqrt3-icosahedron.png
$F render gallery:icosahedron -s butterfly --levels 4 -m highlight --size 240x240 -o docs/images/tri-butterfly-icosahedron.png
