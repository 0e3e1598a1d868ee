#!/usr/bin/env bash
# Regenerates the guide's reference pages from the code: the command-line reference from clap's
# command tree and the scheme catalogue from the registry. tests/it/reference_pages.rs fails while
# the checked-in pages differ from what the binary prints; run this and commit the pages.
#
# Usage: docs/make-reference.sh   (builds the release binary first)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
out=docs/guide/src/reference
mkdir -p "$out"
target/release/fairsub help-markdown > "$out/cli.md.tmp"
mv "$out/cli.md.tmp" "$out/cli.md"
target/release/fairsub schemes --markdown > "$out/schemes.md.tmp"
mv "$out/schemes.md.tmp" "$out/schemes.md"
echo "wrote $out/cli.md ($(wc -l < "$out/cli.md") lines), $out/schemes.md ($(wc -l < "$out/schemes.md") lines)"
