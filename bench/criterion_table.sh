#!/usr/bin/env bash
# The criterion benchmarks' table of the guide's Performance page: runs the cases it shows of
# `benches/refinement.rs` (uniform Catmull-Clark and Loop refinement of closed tori) and all of
# `benches/surfaces.rs` (limit stencils, Bezier conversion, tessellation, EG against
# Catmull-Clark caps), then reads the medians criterion wrote in this run
# (target/criterion/**/new/estimates.json beside new/benchmark.json, only files newer than the
# start of the run) and prints them as two Markdown tables.
#
#   bench/criterion_table.sh         # from anywhere; prints the tables
#   TABLE=docs/guide/src/tables/criterion.md bench/criterion_table.sh   # the guide's table
#
# Environment: TABLE (unset: also write the tables with their generated header, bench/table.sh).
# The refinement cases are a criterion filter (REFINEMENT, a regular expression over the
# benchmark ids; default: the rows of the table below); the benches' own settings (10 samples,
# 1 s of measurement) keep a run to a few minutes on two cores after the build.
set -euo pipefail

. "$(dirname "$0")/table.sh"
cd "$(dirname "$0")/.."
REFINEMENT=${REFINEMENT:-'^(catmull-clark/(topology|geometry|one_shot)/(10k/[34]|1000k/1)|catmull-clark/stencils/10k(-packed)?/3|loop/(topology|geometry|one_shot)/(10k/4|1000k/1))$'}

cargo bench --quiet --bench refinement --bench surfaces --no-run
start=$(date +%s)
sleep 1
echo "load before measuring: $(uptime)"
table_begin bench/criterion_table.sh REFINEMENT
cargo bench --quiet --bench refinement -- "$REFINEMENT"
cargo bench --quiet --bench surfaces
echo "load after measuring: $(uptime)"

python3 - "$start" <<'PY' | tee target/criterion-table.md
import json, os, sys

start = float(sys.argv[1])
median = {}  # full id -> median in ms, of this run only
for root, _, names in os.walk("target/criterion"):
    if os.path.basename(root) != "new" or "benchmark.json" not in names:
        continue
    est = os.path.join(root, "estimates.json")
    if os.path.getmtime(est) < start:
        continue
    with open(os.path.join(root, "benchmark.json")) as f:
        full_id = json.load(f)["full_id"]
    with open(est) as f:
        median[full_id] = json.load(f)["median"]["point_estimate"] / 1e6


def ms(key):
    if key not in median:
        sys.exit(f"criterion_table: no result of this run for {key}")
    v = median[key]
    return f"{v:.3g}" if v < 100 else f"{v:.0f}"


print("| case: median ms | topology | geometry | stencils (plain / packed) | one-shot |")
print("| --- | --- | --- | --- | --- |")
for scheme, label, faces, level, unit in [
    ("catmull-clark", "Catmull-Clark", "10k", 3, "quads"),
    ("catmull-clark", "Catmull-Clark", "10k", 4, "quads"),
    ("catmull-clark", "Catmull-Clark", "1000k", 1, "quads"),
    ("loop", "Loop", "10k", 4, "triangles"),
    ("loop", "Loop", "1000k", 1, "triangles"),
]:
    n = int(faces[:-1]) * 1000
    out = n * 4**level
    size = f"{out / 1e6:.3g}M" if out >= 1e6 else f"{out // 1000}k"
    name = f"{label} {'1M' if faces == '1000k' else faces} {unit}, level {level} ({size} faces)"
    cell = lambda group, f=faces: ms(f"{scheme}/{group}/{f}/{level}")
    # the bench measures stencil tables up to results of about 1M faces
    stencils = (
        f"{cell('stencils')} / {ms(f'{scheme}/stencils/{faces}-packed/{level}')}"
        if out <= 1_100_000
        else "not measured (table too large)"
    )
    print(f"| {name} | {cell('topology')} | {cell('geometry')} | {stencils} | {cell('one_shot')} |")

print()
print("| surfaces: median ms | Catmull-Clark | Loop / EG | ratio |")
print("| --- | --- | --- | --- |")
print(f"| limit positions of a 100k-face torus: build the stencils | {ms('limit/cc-100k/build')} | {ms('limit/loop-100k/build')} | |")
print(f"| the same: apply them | {ms('limit/cc-100k/apply')} | {ms('limit/loop-100k/apply')} | |")
print(f"| Bezier conversion of a 10k-quad torus (6 rings + fill) | {ms('bezier/cc-10k')} | | |")
print(f"| its tessellation, 8 x 8 samples per patch | {ms('tessellate/cc-10k-n8')} | | |")
for n in (3, 5):
    cc, eg = median.get(f"caps/cc/{n}"), median.get(f"caps/eg/{n}")
    ratio = f"EG / CC {eg / cc:.2f}" if cc and eg else ""
    print(f"| convex c-net of valence {n}, 8 rings + fill: CC against EG caps | {ms(f'caps/cc/{n}')} | {ms(f'caps/eg/{n}')} | {ratio} |")
PY
table_write <target/criterion-table.md
