#!/usr/bin/env bash
# Zooms into one cap of each family of schemes, before (the C^0 fill of an older fairsub) and
# after (the G^1 cap), in highlight-line mode, for the README's section on caps.
#   BEFORE=/path/to/old/fairsub docs/make-cap-images.sh
# BEFORE is a fairsub binary built before the caps of issue 17's second round (the README's
# pictures: main at 7a6822f; Loop's: main at 3f0d61c; QAS+^3's and guided-bi4-macro's split
# caps: main at 10bee89; guided-bi3-macro's and adjustable TPS's: 7a6822f; Doo-Sabin's and
# PGS's: e860dfb, before their caps; the cone point's: b941ba1; valence 2: c070068); without it only the "after"
# pictures are made.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
F=target/release/fairsub
look=(--rings 4 --mode highlight --zoom-rings 3..5 --size 300x300 --stripes 16)
# family name, scheme, net, extra options
cases=(
  "eg eg gallery:cnet-5-saddle"
  "qas qas-plus gallery:cnet-6-convex"
  "tps tps gallery:cnet-5-saddle"
  "nonbox nonbox gallery:cnet-6-convex"
  "loop loop gallery:icosahedron --focus vertex:0"
  "qas-plus-bi3 qas-plus-bi3 gallery:cnet-5-saddle"
  "guided-bi4-macro guided-bi4-macro gallery:cnet-5-saddle"
  "guided-bi3-macro guided-bi3-macro gallery:cnet-5-saddle"
  "doo-sabin doo-sabin gallery:cnet-5-saddle"
  "pgs pgs gallery:cnet-5-convex"
  "tps-adjustable tps-adjustable gallery:cnet-5-saddle"
)
for c in "${cases[@]}"; do
  read -r family scheme net extra <<<"$c"
  name=$(basename "$net" .obj)
  name=${name#gallery:}
  $F render "$net" -s "$scheme" "${look[@]}" ${extra:-} -o "docs/images/cap-$family-$name-after.png" >/dev/null
  if [ -n "${BEFORE:-}" ]; then
    "$BEFORE" render "$net" -s "$scheme" "${look[@]}" ${extra:-} -o "docs/images/cap-$family-$name-before.png" >/dev/null
  fi
done
# a cone point (OpenSubdiv's corner tag 10 on a cube vertex without sharp edges), seen along
# the cube's diagonal, the cap and its last ring
cone=(--rings 4 --mode highlight --zoom-rings 5..5 --size 300x300 --stripes 16 --azimuth 45
  --elevation 35 --focus vertex:7)
net=tests/data/osd/cc_corner_tags.obj
$F render "$net" -s catmull-clark "${cone[@]}" -o docs/images/cap-cone-cc_corner_tags-after.png >/dev/null
if [ -n "${BEFORE:-}" ]; then
  "$BEFORE" render "$net" -s catmull-clark "${cone[@]}" -o docs/images/cap-cone-cc_corner_tags-before.png >/dev/null
fi
# valence 2 (half-plane caps): a pentagon's vertex after the first step, and the octahedron read
# by nonbox-4dir as a pillow of two quads (seen from above vertex 0, the cap alone)
for c in "cc catmull-clark docs/nets/split-edge-cube.obj --focus vertex:8 --zoom-rings 4..5" \
         "nonbox-4dir nonbox-4dir gallery:octahedron --focus vertex:0 --zoom-rings 5..5 --azimuth 10 --elevation 20"; do
  read -r family scheme net view <<<"$c"
  name=$(basename "$net" .obj)
  name=${name#gallery:}
  # shellcheck disable=SC2206
  two=(--rings 4 --mode highlight --size 300x300 --stripes 16 $view)
  $F render "$net" -s "$scheme" "${two[@]}" -o "docs/images/cap-valence2-$family-$name-after.png" >/dev/null
  if [ -n "${BEFORE:-}" ]; then
    "$BEFORE" render "$net" -s "$scheme" "${two[@]}" -o "docs/images/cap-valence2-$family-$name-before.png" >/dev/null
  fi
done
