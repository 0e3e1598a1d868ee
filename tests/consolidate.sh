#!/usr/bin/env bash
# Gathers the integration tests into one test binary (issue 51): cargo links one binary against
# the library instead of one per file (52 links took most of a fresh `cargo test --release`).
#
#   tests/NAME.rs      -> tests/it/NAME.rs, declared `mod NAME;` in tests/it/main.rs
#   tests/DIR/*.rs     -> tests/it/DIR/*.rs (helpers the files include by `#[path]`; the data,
#                         scripts and peer sources in tests/DIR stay where they are)
#
# The move is mechanical and may be run again after merging branches that add or edit files
# at the old places (git follows the renames of edited files; new files are moved and declared
# here): `tests/consolidate.sh && cargo test --release --test it`. Each moved file keeps its
# text except for three rewrites that the new place needs:
#   - `include_str!("P")` / `include_bytes!("P")` read relative to the file: one `../` more;
#   - a bare `mod DIR;` (a `tests/DIR/mod.rs` shared by several files) gets `#[path]`, since a
#     module file's children would otherwise be looked up under `tests/it/NAME/`;
#   - in the helpers of tests/DIR, `crate::X` (the file that included the helper was its crate)
#     becomes `super::X` (that file is now the helper's parent module);
#   - a `#[path = "../tests/DIR/F.rs"]` in benches/ (or examples/, src/) follows its file;
#   - nothing else: `env!("CARGO_MANIFEST_DIR")` paths and `env!("CARGO_BIN_EXE_fairsub")` hold.
# Files that change process-wide state keep a binary of their own (listed in `own_process`):
# toy_scheme.rs registers a scheme in the global registry, which the other tests enumerate.
# Cargo finds tests/it/main.rs by itself (a folder under tests/ with a main.rs is a test target).
set -euo pipefail
cd "$(dirname "$0")/.."
it=tests/it
main=$it/main.rs
mkdir -p "$it"

if [ ! -e "$main" ]; then
  cat >"$main" <<'EOF'
//! The integration tests, one module per topic, linked into one test binary (issue 51: one
//! link instead of one per file). `cargo test --release --test it -- NAME::` runs one topic;
//! `tests/consolidate.sh` moved the former `tests/NAME.rs` files here (and moves new ones).

EOF
fi

# One more `../` in front of the relative paths of include_str!/include_bytes!.
deeper() {
  perl -0pi -e 's/\b(include_str|include_bytes)!\(\s*"(?!\/)/$1!("..\//g' "$1"
}

own_process=" toy_scheme "
shopt -s nullglob
for f in tests/*/*.rs; do
  case "$f" in "$it"/*) continue ;; esac
  d=$(basename "$(dirname "$f")")
  mkdir -p "$it/$d"
  git mv -k "$f" "$it/$d/"
  deeper "$it/$d/$(basename "$f")"
  perl -pi -e 's/\bcrate::/super::/g' "$it/$d/$(basename "$f")"
  rmdir "$(dirname "$f")" 2>/dev/null || true # a folder of helpers only
done
for f in tests/*.rs; do
  name=$(basename "$f" .rs)
  case "$own_process" in *" $name "*) continue ;; esac
  git mv -k "$f" "$it/"
  deeper "$it/$name.rs"
  # A bare `mod DIR;` of a shared tests/DIR/mod.rs (no #[path] on the line before).
  perl -0pi -e 's/(^|\n)(?<!\]\n)mod (\w+);/my ($p, $m) = ($1, $2); -e "tests\/it\/$m\/mod.rs" ? "$p#[path = \"$m\/mod.rs\"]\nmod $m;" : "${p}mod $m;"/ge' "$it/$name.rs"
  grep -qx "mod $name;" "$main" || echo "mod $name;" >>"$main"
done
# Other targets that include a moved helper by #[path] (benches/viewer_fps.rs uses the viewer
# tests' DevTools client).
for f in $(grep -rl --include='*.rs' '"\.\./tests/[a-z_0-9]*/[a-z_0-9]*\.rs"' benches bench examples src 2>/dev/null); do
  perl -pi -e 's{"\.\./tests/(?!it/)([a-z_0-9]+/[a-z_0-9]+\.rs)"}{-e "tests/it/$1" ? "\"../tests/it/$1\"" : "\"../tests/$1\""}ge' "$f"
done
