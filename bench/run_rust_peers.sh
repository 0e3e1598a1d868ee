#!/usr/bin/env bash
# fairsub against the two Rust subdivision crates (opensubdiv-rs, subdiv-kernels), in process,
# on the same meshes as bench/run_peer.sh (issue 49); OpenSubdiv itself is bench/run_peer.sh.
#
#   bench/run_rust_peers.sh        # from anywhere; FACES (100k), LEVELS (3), REPS (1)
#
# Builds bench/rust-peers/ (its own workspace, so the main crate's builds and tests never compile
# the two crates) into the root's target directory, starting from the root's Cargo.lock so that
# fairsub and its dependencies are the ones already built. Prints, per mesh, the check that both
# crates' refined points equal fairsub's (matched by coordinates, faces then compared), and the
# table of times with the ratios. Takes about a minute on two idle cores at 100k faces.
# TABLE (unset) also writes both tables as Markdown with their generated header
# (bench/table.sh); the guide's are written by
#   TABLE=docs/guide/src/tables/rust-peers.md bench/run_rust_peers.sh
set -euo pipefail

. "$(dirname "$0")/table.sh"
ROOT=$(cd "$(dirname "$0")/.." && pwd)
FACES=${FACES:-100k}
LEVELS=${LEVELS:-3}
REPS=${REPS:-1}
cd "$ROOT/bench/rust-peers"
[ -f Cargo.lock ] || cp "$ROOT/Cargo.lock" Cargo.lock
CARGO_TARGET_DIR="$ROOT/target" cargo build --release --quiet
echo "load before measuring: $(uptime)"
table_begin bench/run_rust_peers.sh FACES LEVELS REPS
"$ROOT/target/release/fairsub-rust-peers" "$FACES" "$LEVELS" "$REPS" "$ROOT/target/rust-peers.md"
echo "load after measuring: $(uptime)"
table_write <"$ROOT/target/rust-peers.md"
