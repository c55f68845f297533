#!/usr/bin/env bash
# Level sets of the shared OpenMandible case (bone + 14 teeth) with `jawmesh levelset`, one process
# per file, at --voxel (default 0.05 mm). Repeats the whole set RUNS times (default 3) and prints a
# Markdown table fragment: per file the median wall time and peak resident memory, then the
# median of the whole set (sum of the files' wall times per run; peak = largest process).
# Usage: bench/levelsets.sh [path/to/jawmesh] [voxel_mm] [runs]
# Environment: JAWMESH_DATA (default: ../shared/data beside the checkout), THREADS (default 0 = all).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
jawmesh="${1:-$here/../build/cli/jawmesh}"
voxel="${2:-0.05}"
runs="${3:-3}"
data="${JAWMESH_DATA:-$here/../../shared/data}/openmandible/input/mandible"
threads="${THREADS:-0}"
[ -x "$jawmesh" ] || { echo "no jawmesh executable at $jawmesh (build it, or pass its path)" >&2; exit 1; }
[ -d "$data" ] || { echo "no shared data at $data" >&2; exit 1; }
command -v python3 >/dev/null || { echo "python3 is needed to read the --json output" >&2; exit 1; }
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

files=("$data/bone/mandible.stl")
for f in "$data"/teeth/tooth_*.stl; do files+=("$f"); done

results="$out/results.tsv"
: > "$results"
for run in $(seq 1 "$runs"); do
  for f in "${files[@]}"; do
    name="$(basename "$f" .stl)"
    start=$(date +%s.%N)
    json="$("$jawmesh" --quiet --threads "$threads" levelset "$f" -o "$out/$name.vdb" --voxel "$voxel" --json)"
    end=$(date +%s.%N)
    printf '%s\t%s\t%s\t%s\n' "$run" "$name" "$(echo "$end - $start" | bc)" "$json" >> "$results"
  done
done

python3 - "$results" "$voxel" "$runs" <<'PY'
import json, statistics, sys
from collections import defaultdict
path, voxel, runs = sys.argv[1], sys.argv[2], int(sys.argv[3])
rows = defaultdict(list)
per_run_wall = defaultdict(float)
per_run_peak = defaultdict(int)
for line in open(path):
    run, name, wall, js = line.rstrip("\n").split("\t", 3)
    j = json.loads(js)
    rows[name].append((float(wall), j["peak_memory_bytes"], j["active_voxels"], j["input_triangles"], j["stage_seconds"], j["sign"]))
    per_run_wall[run] += float(wall)
    per_run_peak[run] = max(per_run_peak[run], j["peak_memory_bytes"])
print(f"Level sets at {voxel} mm, median of {runs} runs (one process per file):\n")
print("| file | triangles | active voxels | wall s | peak MB | unsigned s | scanlines s | sign s | fallback voxels |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
for name in sorted(rows, key=lambda n: (not n.startswith("mandible"), n)):
    r = rows[name]
    med = lambda k: statistics.median(x[k] for x in r)
    st = lambda key: statistics.median(x[4][key] for x in r)
    print(f"| {name} | {r[0][3]:,} | {r[0][2]:,} | {med(0):.2f} | {med(1)/2**20:.0f} | {st('unsigned'):.2f} | "
          f"{st('scanlines'):.2f} | {st('sign'):.2f} | {statistics.median(x[5]['fallback_voxels'] for x in r):,.0f} |")
print(f"| **bone + {len(rows)-1} teeth** | | | **{statistics.median(per_run_wall.values()):.2f}** | "
      f"**{statistics.median(per_run_peak.values())/2**20:.0f}** (largest process) | | | | |")
PY
