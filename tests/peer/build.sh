#!/usr/bin/env bash
# Builds the OpenSubdiv peer of tests/it/osd_peer.rs: target/peer/osd_refine from
# tests/peer/osd_refine.cpp against Debian's libosd-dev (OpenSubdiv 3.5).
#
#   tests/peer/build.sh            # from anywhere; prints the path of the program
#   tests/peer/build.sh run ARGS   # builds if needed, then runs osd_refine ARGS
#
# Installs libosd-dev and g++ with apt-get when they are missing (through sudo unless run as
# root). Idempotent: rebuilds only when the source is newer than the program, so a second
# call returns at once.
set -euo pipefail

root="$(cd "$(dirname "$0")/../.." && pwd)"
src="$root/tests/peer/osd_refine.cpp"
out="$root/target/peer/osd_refine"

need=()
[ -f /usr/include/opensubdiv/far/topologyRefinerFactory.h ] || need+=(libosd-dev)
command -v g++ >/dev/null 2>&1 || need+=(g++)
if [ ${#need[@]} -gt 0 ]; then
    echo "build.sh: installing ${need[*]}" >&2
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo=sudo
    $sudo apt-get update -qq >&2
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${need[@]}" >&2
fi

if [ ! -x "$out" ] || [ "$src" -nt "$out" ]; then
    mkdir -p "$(dirname "$out")"
    g++ -O2 -std=c++17 -Wall -Wextra -o "$out.tmp" "$src" -losdCPU
    mv "$out.tmp" "$out"
fi

if [ "${1:-}" = run ]; then
    shift
    exec "$out" "$@"
fi
echo "$out"
