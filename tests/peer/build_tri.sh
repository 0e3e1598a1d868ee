#!/usr/bin/env bash
# Builds the sqrt(3) and modified butterfly peers of tests/it/peer_sqrt3_butterfly.rs:
# target/peer/cgal_sqrt3 (CGAL's Sqrt3_subdivision, Debian libcgal-dev, header-only) and
# target/peer/om_butterfly (OpenMesh's ModifiedButterflyT, Debian libopenmesh-dev), from
# tests/peer/cgal_sqrt3.cpp and tests/peer/om_butterfly.cpp with tests/peer/tri_io.h.
#
#   tests/peer/build_tri.sh        # from anywhere; prints the paths of the two programs
#
# Installs the packages and g++ with apt-get when missing (through sudo unless run as root).
# Idempotent: rebuilds a program only when its sources are newer.
set -euo pipefail

root="$(cd "$(dirname "$0")/../.." && pwd)"
dir="$root/tests/peer"
outdir="$root/target/peer"

need=()
[ -f /usr/include/CGAL/subdivision_method_3.h ] || need+=(libcgal-dev)
[ -f /usr/include/OpenMesh/Tools/Subdivider/Uniform/ModifiedButterFlyT.hh ] || need+=(libopenmesh-dev)
command -v g++ >/dev/null 2>&1 || need+=(g++)
if [ ${#need[@]} -gt 0 ]; then
    echo "build_tri.sh: installing ${need[*]}" >&2
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo=sudo
    $sudo apt-get update -qq >&2
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${need[@]}" >&2
fi

mkdir -p "$outdir"
build() { # NAME LIBS...
    local name="$1"; shift
    local src="$dir/$name.cpp" out="$outdir/$name"
    if [ ! -x "$out" ] || [ "$src" -nt "$out" ] || [ "$dir/tri_io.h" -nt "$out" ]; then
        g++ -O2 -std=c++17 -Wall -Wextra -o "$out.tmp" "$src" "$@"
        mv "$out.tmp" "$out"
    fi
    echo "$out"
}
build cgal_sqrt3 -lgmp -lmpfr
build om_butterfly -lOpenMeshTools -lOpenMeshCore
