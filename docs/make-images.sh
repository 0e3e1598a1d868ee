#!/usr/bin/env bash
# Regenerates the pictures of the README and the user guide from the built-in gallery (deterministic output).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
F=target/release/fairsub
common=(--rings 10 --size 240x240 --elevation 70 --modes highlight,gauss)
# Catmull-Clark alone on the valence-5 saddle (README, guide: classic schemes, rendering).
$F compare gallery:cnet-5-saddle --schemes catmull-clark --modes highlight,mean,provenance --size 320x320 --zoom-rings 1..7 --elevation 55 -o docs/images/compare-cnet-5-saddle.png
$F compare gallery:cnet-5-saddle --schemes catmull-clark,eg,qas-plus --zoom-rings 3..11 "${common[@]}" -o docs/images/cc-eg-qas-cnet-5-saddle.png
$F compare gallery:cnet-6-convex --schemes catmull-clark,qas-plus --zoom-rings 3..11 "${common[@]}" -o docs/images/cc-qas-cnet-6-convex.png
$F compare gallery:cnet-7-saddle --schemes catmull-clark,qas-plus --zoom-rings 3..11 "${common[@]}" -o docs/images/cc-qas-cnet-7-saddle.png
$F compare gallery:cnet-5-planar --schemes catmull-clark,eg,qas-plus --zoom-rings 1..11 "${common[@]}" -o docs/images/cc-eg-qas-cnet-5-planar.png
# The bi-2 family: Doo-Sabin against PGS on convex and saddle nets, a prism under Doo-Sabin,
# PGS (plain and after two DS^CC steps) and PolBS, and the mixed net (example bi2_mixed).
bi2=(--size 200x200 --stripes 20 --modes highlight,mean)
$F compare gallery:cnet-5-convex --schemes doo-sabin,pgs --zoom-rings 1..6 --rings 10 --elevation 60 "${bi2[@]}" -o docs/images/ds-pgs-cnet-5-convex.png
$F compare gallery:cnet-5-saddle --schemes doo-sabin,pgs --zoom-rings 1..6 --rings 10 --elevation 60 "${bi2[@]}" -o docs/images/ds-pgs-cnet-5-saddle.png
$F compare gallery:prism-5 --schemes doo-sabin,pgs,pgs-dscc,polar-bi2 --rings 8 --elevation 50 --size 180x180 --stripes 16 --modes highlight,mean -o docs/images/prism-5-ds-pgs-polbs.png
tmp=$(mktemp -d)
cargo run --release --quiet --example bi2_mixed -- "$tmp" >/dev/null
$F compare "$tmp/bi2-mixed-net.obj" --schemes bi2-mixed --rings 4 --size 200x200 --elevation 35 --stripes 16 --modes provenance,highlight,mean -o docs/images/bi2-mixed-prism.png
rm -rf "$tmp"
# Guided subdivision beside Catmull-Clark, EG and QAS+ (rows chosen when EG had rules for 3 and 5
# only and QAS+ for 5..7; the derived rules at other valences are in make-derived-images.sh).
for shape in convex saddle planar raised; do
  $F compare gallery:cnet-5-$shape --schemes catmull-clark,eg,qas-plus,guided-bi5,guided-bi6 --zoom-rings 1..11 "${common[@]}" -o docs/images/guided-cnet-5-$shape.png
done
$F compare gallery:cnet-3-saddle --schemes catmull-clark,eg,guided-bi5,guided-bi6 --zoom-rings 1..11 "${common[@]}" -o docs/images/guided-cnet-3-saddle.png
$F compare gallery:cnet-7-planar --schemes catmull-clark,qas-plus,guided-bi5,guided-bi6-half --zoom-rings 1..11 "${common[@]}" -o docs/images/guided-cnet-7-planar.png
$F compare gallery:cnet-8-raised --schemes catmull-clark,guided-bi5,guided-bi6,guided-bi5-half --zoom-rings 1..11 "${common[@]}" -o docs/images/guided-cnet-8-raised.png
$F compare gallery:cnet-10-convex --schemes catmull-clark,guided-bi5,guided-bi5-half --zoom-rings 1..11 "${common[@]}" -o docs/images/guided-cnet-10-convex.png
# The macro-patch variants (Section 6.2, fairsub's derivation; no cap: the hole stays open).
$F compare gallery:cnet-5-raised --schemes guided-bi5,guided-bi4-macro,guided-bi3-macro --zoom-rings 1..11 --no-fill "${common[@]}" -o docs/images/guided-macro-cnet-5-raised.png
