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
#   - a helper file that several modules include by `#[path = "DIR/F.rs"] mod F;` is declared
#     once in main.rs (module `DIR_helpers::F`, or `DIR` for a `DIR/mod.rs`), and each of them
#     `use`s it instead (a file loaded as several modules is compiled once per copy, and
#     clippy's duplicate_mod refuses it);
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
# Helpers included by several modules: declared once in main.rs, `use`d by the modules.
python3 - "$it" <<'PY'
import collections, os, re, sys
it = sys.argv[1]
main = os.path.join(it, "main.rs")
tops = sorted(f for f in os.listdir(it) if f.endswith(".rs") and f not in ("main.rs", "common.rs"))
pat = re.compile(r'#\[path = "(\w+)/(\w+)\.rs"\]\n((?:#\[[^\n]*\]\n)*)mod (\w+);\n')
begin, end = "// Helpers shared by several modules (tests/consolidate.sh).\n", "// End of the shared helpers.\n"
text = open(main).read()
shared = set()
if begin in text:
    block = text[text.index(begin):text.index(end)]
    shared |= set(re.findall(r'#\[path = "(\w+)/(mod)\.rs"\]', block))
    for d, body in re.findall(r'#\[path = "(\w+)"\]\nmod \w+_helpers \{\n(.*?)\n\}', block, re.S):
        shared |= {(d, s) for s in re.findall(r'#\[path = "(\w+)\.rs"\]', body)}
includers = collections.defaultdict(set)
for f in tops:
    for m in pat.finditer(open(os.path.join(it, f)).read()):
        includers[(m.group(1), m.group(2))].add(f)
shared |= {k for k, v in includers.items() if len(v) > 1}
for f in tops:  # modules that already use a shared helper
    src = open(os.path.join(it, f)).read()
    shared |= set(re.findall(r'^use crate::(\w+)_helpers::(\w+)\b', src, re.M))
    shared |= {(d, "mod") for d in re.findall(r'^use crate::(\w+);', src, re.M)
               if os.path.exists(os.path.join(it, d, "mod.rs"))}
def path_of(d, stem):
    return f"crate::{d}" if stem == "mod" else f"crate::{d}_helpers::{stem}"
for f in tops:
    p = os.path.join(it, f)
    src = open(p).read()
    def repl(m):
        d, stem, _, name = m.groups()
        if (d, stem) not in shared:
            return m.group(0)
        target = path_of(d, stem)
        last = target.rsplit("::", 1)[1]
        return f"use {target};\n" if last == name else f"use {target} as {name};\n"
    new = pat.sub(repl, src)
    if new != src:
        open(p, "w").write(new)
lines = [begin]
for d in sorted({d for d, _ in shared}):
    if (d, "mod") in shared:
        lines.append(f'#[allow(dead_code)]\n#[path = "{d}/mod.rs"]\nmod {d};\n')
    stems = sorted(s for dd, s in shared if dd == d and s != "mod")
    if stems:
        lines.append(f'#[allow(dead_code)]\n#[path = "{d}"]\nmod {d}_helpers {{\n')
        for s in stems:
            lines.append(f'    #[path = "{s}.rs"]\n    pub mod {s};\n')
        lines.append("}\n")
lines.append(end)
if begin in text:
    text = text[:text.index(begin)] + "".join(lines) + text[text.index(end) + len(end):]
else:
    text = text.rstrip("\n") + "\n\n" + "".join(lines)
open(main, "w").write(text)
PY
