#!/usr/bin/env bash
# Regenerates the pictures of the README from the built-in gallery (deterministic output).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
F=target/release/fairsub
common=(--rings 10 --size 240x240 --elevation 70 --modes highlight,gauss)
$F compare gallery:cnet-5-saddle --schemes catmull-clark,eg,qas-plus --zoom-rings 3..11 "${common[@]}" -o docs/images/cc-eg-qas-cnet-5-saddle.png
$F compare gallery:cnet-6-convex --schemes catmull-clark,qas-plus --zoom-rings 3..11 "${common[@]}" -o docs/images/cc-qas-cnet-6-convex.png
$F compare gallery:cnet-7-saddle --schemes catmull-clark,qas-plus --zoom-rings 3..11 "${common[@]}" -o docs/images/cc-qas-cnet-7-saddle.png
$F compare gallery:cnet-5-planar --schemes catmull-clark,eg,qas-plus --zoom-rings 1..11 "${common[@]}" -o docs/images/cc-eg-qas-cnet-5-planar.png
