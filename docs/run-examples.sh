#!/usr/bin/env bash
# Runs every example command of the README and the user guide, so that what the pages show
# works (CI runs this after the release build).
#
# The contract for the pages:
# - A fenced block whose info string is exactly `sh` is an example and is run; `console`, `text`,
#   `python` (and every other info string) are shown only. A block that cannot run here (an
#   interactive `fairsub view`, a path of the reader's own, a download) is marked `console`.
# - Each block runs on its own with `bash -e` (the first failing command ends it), within a time
#   limit, in a fresh temporary directory holding symbolic links to the repository's top-level
#   entries (gallery/, docs/, examples/, tests/, python/, ...; not .git or target/), with the
#   release `fairsub` binary (target/release/fairsub) first on the PATH. So a block may read
#   `docs/nets/...` or `gallery/...` and write files of its own next to them; it cannot see
#   what another block wrote.
# - A block must not change the repository through the links (`git status` before and after
#   each block): write outputs into the scratch folder, not into docs/ or gallery/.
# - On a failure the runner prints the page and line of the failing command, the command, and
#   the block's standard error, and exits with 1 after running the other blocks.
#
# Usage: docs/run-examples.sh [PAGE.md ...]   (default: README.md and docs/guide/src/**/*.md)
#        docs/run-examples.sh --list [PAGE.md ...]   (print the blocks' places, run nothing)
# Variables: FAIRSUB_EXAMPLE_TIMEOUT (seconds per block, default 300).
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
list=0
if [ "${1:-}" = "--list" ]; then
  list=1
  shift
fi
pages=("$@")
if [ ${#pages[@]} -eq 0 ]; then
  pages=("$repo/README.md")
  while IFS= read -r p; do pages+=("$p"); done < <(find "$repo/docs/guide/src" -name '*.md' | LC_ALL=C sort)
fi
limit=${FAIRSUB_EXAMPLE_TIMEOUT:-300}

binary="$repo/target/release/fairsub"
if [ $list -eq 0 ] && [ ! -x "$binary" ]; then
  echo "run-examples: $binary is missing (cargo build --release first)" >&2
  exit 1
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir "$work/bin" "$work/blocks"
ln -s "$binary" "$work/bin/fairsub"

# Extract the blocks: blocks/N.sh holds block N's lines (indentation of its fence removed) and
# blocks/index has "N<TAB>page<TAB>line of the first command" per block.
n=0
for page in "${pages[@]}"; do
  [ -f "$page" ] || { echo "run-examples: no page $page" >&2; exit 1; }
  rel=${page#"$repo"/}
  n=$(awk -v out="$work/blocks" -v rel="$rel" -v n="$n" '
    !inb && match($0, /^[ \t]*(```+|~~~+)/) {
      pre = $0; sub(/[`~].*$/, "", pre); indent = length(pre)
      fence = substr($0, indent + 1, RLENGTH - indent)
      info = substr($0, RLENGTH + 1); gsub(/^[ \t]+|[ \t]+$/, "", info)
      inb = 1; run = (info == "sh")
      if (run) {
        n++; file = out "/" n ".sh"; printf "" > file
        printf "%d\t%s\t%d\n", n, rel, NR + 1 >> (out "/index")
      }
      next
    }
    inb {
      s = $0; sub(/^[ \t]+/, "", s); c = substr(fence, 1, 1)
      if (s ~ /^(```+|~~~+)[ \t]*$/ && substr(s, 1, 1) == c) {
        f = s; sub(/[ \t]*$/, "", f)
        if (length(f) >= length(fence)) {
          if (run) close(file)
          inb = 0; run = 0; next
        }
      }
      if (run) {
        # the fence indentation goes (a block inside a list item)
        line = $0
        for (i = 0; i < indent && line ~ /^[ \t]/; i++) line = substr(line, 2)
        print line >> file
      }
    }
    END { print n }
  ' "$page")
done

if [ ! -f "$work/blocks/index" ]; then
  echo "run-examples: no sh blocks in ${#pages[@]} pages"
  exit 0
fi
if [ $list -eq 1 ]; then
  cut -f2,3 "$work/blocks/index" | tr '\t' ':'
  exit 0
fi

# `git status` of the repository, to catch a block that writes through the links.
repo_state() {
  git -C "$repo" status --porcelain --untracked-files=all 2>/dev/null || true
}

passed=0
failed=0
while IFS=$'\t' read -r i page line; do
  dir="$work/run-$i"
  mkdir "$dir"
  for entry in "$repo"/* "$repo"/.[!.]*; do
    name=$(basename "$entry")
    case "$name" in .git | target | '.[!.]*') continue ;; esac
    [ -e "$entry" ] && ln -s "$entry" "$dir/$name"
  done
  # the ERR trap records the failing command and its line within the block
  {
    printf '%s\n' "trap 'printf \"%s\\t%s\\n\" \"\$LINENO\" \"\$BASH_COMMAND\" > \"$work/failed-$i\"' ERR"
    cat "$work/blocks/$i.sh"
  } > "$work/script-$i.sh"
  before=$(repo_state)
  set +e
  (cd "$dir" && PATH="$work/bin:$PATH" timeout "$limit" bash -e "$work/script-$i.sh") \
    > "$work/out-$i" 2> "$work/err-$i" < /dev/null
  rc=$?
  set -e
  after=$(repo_state)
  wrote=0
  if [ $rc -eq 0 ] && [ "$before" != "$after" ]; then
    rc=1
    wrote=1
    diff <(printf '%s\n' "$before") <(printf '%s\n' "$after") | sed -n 's/^> //p' >> "$work/err-$i"  || true
  fi
  if [ $rc -eq 0 ]; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    if [ -s "$work/failed-$i" ]; then
      IFS=$'\t' read -r at cmd < "$work/failed-$i"
      where=$((line + at - 2))
    else
      where=$line
      cmd="(the block)"
      [ $rc -eq 124 ] && cmd="(the block ran over ${limit} s)"
      [ $wrote -eq 1 ] && cmd="(the block wrote into the repository; git status shows)"
    fi
    echo "FAILED $page:$where: $cmd (exit code $rc)"
    sed 's/^/  | /' "$work/err-$i" | tail -n 40
  fi
  rm -rf "$dir"
done < "$work/blocks/index"

echo "examples: $passed passed, $failed failed"
[ $failed -eq 0 ]
