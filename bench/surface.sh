#!/usr/bin/env bash
# Interface extraction + simplification (`jawmesh surface ... --json`, issue #4) on a carved label
# field, with `jawmesh run`'s defaults (the command's own since session 16). Runs RUNS
# times (default 3, at least 3 for a median) and prints Markdown: the median extraction,
# simplification and total seconds, the process's peak resident memory, then the triangles per
# interface kind, the largest tracked error and the smallest angle of the last run.
# Usage: bench/surface.sh <carve-dir> [path/to/jawmesh] [runs]
#   carve-dir: a jaw folder of `jawmesh carve` or of `jawmesh run --write-levelsets` (e.g. the
#   shared mandible: jawmesh run ../shared/data/openmandible -o out --jaw mandible --write-levelsets,
#   then out/mandible)
# Environment: THREADS (default 0 = all), PDL_MAX_EDGE (default: the command's, 0.8).
source "$(dirname "$0")/common.sh"
carve="${1:?usage: bench/surface.sh <carve-dir> [jawmesh] [runs]}"
jawmesh="${2:-$here/../build/cli/jawmesh}"
runs="${3:-3}"
require_jawmesh "$jawmesh"
[ -e "$carve/labels.vdb" ] || [ -e "$carve/levelsets/labels.vdb" ] || { echo "no label field in $carve" >&2; exit 1; }
require_runs "$runs"
require_python3
make_results_file out results
for run in $(seq 1 "$runs"); do
  "$jawmesh" --quiet --threads "$threads" surface "$carve" -o "$out/run$run" \
    ${PDL_MAX_EDGE:+--pdl-max-edge "$PDL_MAX_EDGE"} --json | tail -1 >> "$results"
  rm -rf "$out/run$run"
done
python3 - "$results" "$(nproc)" "$(cut -d' ' -f1-3 /proc/loadavg)" <<'PY'
import json, statistics, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
med = statistics.median
print(f"`jawmesh surface`, median of {len(rows)} runs, {sys.argv[2]} cores, load at the end {sys.argv[3]}:\n")
print("| extraction s | simplification s | extraction + simplification s | total s | peak MB |")
print("|---:|---:|---:|---:|---:|")
s = [r["seconds"] for r in rows]
print(f"| {med(x['extract'] for x in s):.1f} | {med(x['simplify'] for x in s):.1f} | "
      f"{med(x['extract'] + x['simplify'] for x in s):.1f} | {med(x['total'] for x in s):.1f} | "
      f"{med(r['peak_memory_bytes'] for r in rows) / 2**20:.0f} |")
last = rows[-1]["simplify"]
print(f"\n{rows[-1]['triangles']} triangles: {last['triangles_per_kind']}; max error {last['max_error_mm']:.4f} mm "
      f"({last['max_error_near_teeth_mm']:.4f} near the teeth), min angle {last['min_angle_deg']:.1f} deg")
PY
