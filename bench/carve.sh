#!/usr/bin/env bash
# PDL carving of the shared OpenMandible case (bone + 14 teeth) with `jawmesh carve ... --json`, at
# --voxel (default 0.05 mm). Runs RUNS times (default 3, at least 3 for a median) and prints Markdown:
# one row with the median carving time, level-set time, total time and peak resident memory, then
# the median seconds and peak memory of every stage (load, level sets, each carving stage).
# Usage: bench/carve.sh [path/to/jawmesh] [voxel_mm] [runs]
# Environment: JAWMESH_DATA (default: ../shared/data beside the checkout), THREADS (default 0 = all).
source "$(dirname "$0")/common.sh"
jawmesh="${1:-$here/../build/cli/jawmesh}"
voxel="${2:-0.05}"
runs="${3:-3}"
require_jawmesh "$jawmesh"
require_mandible_case case_dir
require_runs "$runs"
require_python3
make_results_file out results

for run in $(seq 1 "$runs"); do
  start=$(date +%s.%N)
  json="$("$jawmesh" --quiet --threads "$threads" carve "$case_dir" -o "$out/run$run" --voxel "$voxel" --json)"
  end=$(date +%s.%N)
  python3 -c 'import json,sys; j=json.loads(sys.argv[1]); j["wall"]=float(sys.argv[2]); print(json.dumps(j))' \
    "$json" "$(echo "$end - $start" | bc)" >> "$results"
  rm -rf "$out/run$run"
done

python3 - "$results" "$voxel" "$runs" "$(nproc)" "$(cut -d' ' -f1-3 /proc/loadavg)" <<'PY'
import json, statistics, sys
path, voxel, runs, cores, load = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4], sys.argv[5]
rs = [json.loads(l) for l in open(path)]
med = lambda xs: statistics.median(xs)
mb = lambda b: b / 2**20
teeth = len(rs[0]["teeth"])
print(f"Carving OpenMandible ({teeth} teeth) at {voxel} mm, median of {runs} runs, {cores} cores, "
      f"load average at the end {load}:\n")
print("| case | voxel mm | carve s | level sets s | total s (process) | peak MB |")
print("|---|---:|---:|---:|---:|---:|")
print(f"| openmandible | {voxel} | {med(r['seconds']['carve'] for r in rs):.1f} | "
      f"{med(r['seconds']['level_sets'] for r in rs):.1f} | {med(r['wall'] for r in rs):.1f} | "
      f"{mb(med(r['peak_memory_bytes'] for r in rs)):.0f} |")
print("\n| stage | s | peak MB at end |")
print("|---|---:|---:|")
for i, st in enumerate(rs[0].get("stages", [])):
    print(f"| {st['name']} | {med(r['stages'][i]['seconds'] for r in rs):.2f} | "
          f"{mb(med(r['stages'][i]['peak_memory_bytes'] for r in rs)):.0f} |")
PY
