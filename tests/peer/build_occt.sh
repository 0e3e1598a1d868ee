#!/usr/bin/env bash
# Builds the OpenCASCADE peer of tests/it/step_peer.rs: target/peer/occt_step from
# tests/peer/occt_step.cpp against Debian's OpenCASCADE 7.6 (libocct-data-exchange-dev and
# the libraries it depends on).
#
#   tests/peer/build_occt.sh            # from anywhere; prints the path of the program
#   tests/peer/build_occt.sh run ARGS   # builds if needed, then runs occt_step ARGS
#
# Installs libocct-data-exchange-dev and g++ with apt-get when they are missing (through sudo
# unless run as root). Idempotent: rebuilds only when the source is newer than the program.
set -euo pipefail

root="$(cd "$(dirname "$0")/../.." && pwd)"
src="$root/tests/peer/occt_step.cpp"
out="$root/target/peer/occt_step"

need=()
[ -f /usr/include/opencascade/STEPControl_Reader.hxx ] || need+=(libocct-data-exchange-dev)
command -v g++ >/dev/null 2>&1 || need+=(g++)
if [ ${#need[@]} -gt 0 ]; then
    echo "build_occt.sh: installing ${need[*]}" >&2
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo=sudo
    $sudo apt-get update -qq >&2
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${need[@]}" >&2
fi

if [ ! -x "$out" ] || [ "$src" -nt "$out" ]; then
    mkdir -p "$(dirname "$out")"
    g++ -O2 -std=c++17 -Wall -Wextra -Wno-deprecated-declarations -I/usr/include/opencascade \
        -o "$out.tmp" "$src" \
        -lTKSTEP -lTKXSBase -lTKShHealing -lTKTopAlgo -lTKGeomAlgo -lTKBRep -lTKGeomBase \
        -lTKG3d -lTKG2d -lTKMath -lTKernel
    mv "$out.tmp" "$out"
fi

if [ "${1:-}" = run ]; then
    shift
    exec "$out" "$@"
fi
echo "$out"
