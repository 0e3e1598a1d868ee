#!/usr/bin/env bash
# The README's panels of EG and QAS+ with derived rules (issue 15): highlight lines and Gauss
# curvature, Catmull-Clark, EG, QAS+ and guided subdivision (bi-5) on the saddle c-nets of
# valence 6, 7, 8, 10 (gallery) and 12, 16 (docs/nets, gallery::cnet(n, Saddle, 3) as OBJ).
# At 6..16 EG uses fairsub's derived rules, QAS+ at 8..16 (printed tables at 6, 7).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
F=target/release/fairsub
common=(--schemes catmull-clark,eg,qas-plus,guided-bi5 --rings 10 --zoom-rings 3..11
  --size 160x160 --elevation 70 --modes highlight,gauss)
for n in 6 7 8 10 12 16; do
  net=gallery:cnet-$n-saddle
  [ "$n" -gt 10 ] && net=docs/nets/cnet-$n-saddle.obj
  $F compare "$net" "${common[@]}" -o docs/images/derived-cnet-$n-saddle.png
done
