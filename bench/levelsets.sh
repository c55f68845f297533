#!/usr/bin/env bash
# Level sets of the shared OpenMandible case (bone + 14 teeth) with `jawmesh levelset`, one process
# per file, at --voxel (default 0.05 mm). Repeats the whole set RUNS times (default 3) and prints a
# Markdown table fragment: per file the median wall time, CPU time (user + sys) and peak resident
# memory (from /usr/bin/time), and the median per-stage seconds of meshToLevelSet; then the
# median of the whole set (sum over the files per run; peak = largest process). The load average
# before and after is printed too: on a shared machine wall time means little without it.
# Usage: bench/levelsets.sh [path/to/jawmesh] [voxel_mm] [runs]
# Environment: JAWMESH_DATA (default: ../shared/data beside the checkout), THREADS (default 0 = all).
source "$(dirname "$0")/common.sh"
jawmesh="${1:-$here/../build/cli/jawmesh}"
voxel="${2:-0.05}"
runs="${3:-3}"
data="${JAWMESH_DATA:-$here/../../shared/data}/openmandible/input/mandible"
require_jawmesh "$jawmesh"
require_folder "$data" "shared data"
require_time
require_python3
make_work_dir out

files=("$data/bone/mandible.stl")
for f in "$data"/teeth/tooth_*.stl; do files+=("$f"); done

results="$out/results.tsv"
: > "$results"
load_before="$(cut -d' ' -f1-3 /proc/loadavg)"
for run in $(seq 1 "$runs"); do
  for f in "${files[@]}"; do
    name="$(basename "$f" .stl)"
    json="$(/usr/bin/time -f '%e %U %S %M' -o "$out/time.txt" \
      "$jawmesh" --quiet --threads "$threads" levelset "$f" -o "$out/$name.vdb" --voxel "$voxel" --json)"
    read -r wall user sys maxrss_kb < "$out/time.txt"
    printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$run" "$name" "$wall" "$(echo "$user + $sys" | bc)" "$maxrss_kb" "$json" >> "$results"
  done
done
load_after="$(cut -d' ' -f1-3 /proc/loadavg)"

python3 - "$results" "$voxel" "$runs" "$load_before" "$load_after" "$(nproc)" <<'PY'
import json, statistics, sys
from collections import defaultdict
path, voxel, runs, load_before, load_after, cores = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4], sys.argv[5], sys.argv[6]
rows = defaultdict(list)
per_run = defaultdict(lambda: [0.0, 0.0, 0])
for line in open(path):
    run, name, wall, cpu, rss_kb, js = line.rstrip("\n").split("\t", 5)
    j = json.loads(js)
    rows[name].append(dict(wall=float(wall), cpu=float(cpu), peak=int(rss_kb) * 1024, j=j))
    per_run[run][0] += float(wall)
    per_run[run][1] += float(cpu)
    per_run[run][2] = max(per_run[run][2], int(rss_kb) * 1024)
print(f"Level sets at {voxel} mm, median of {runs} runs, one process per file, {cores} cores; "
      f"load average (1/5/15 min) {load_before} before, {load_after} after.\n")
print("| file | triangles | active voxels | wall s | CPU s | peak MB | orient s | unsigned s | scanlines s | sign s |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for name in sorted(rows, key=lambda n: (not n.startswith("mandible"), n)):
    r = rows[name]
    med = lambda key: statistics.median(x[key] for x in r)
    st = lambda key: statistics.median(x["j"]["stage_seconds"][key] for x in r)
    j = r[0]["j"]
    print(f"| {name} | {j['input_triangles']:,} | {j['active_voxels']:,} | {med('wall'):.2f} | {med('cpu'):.2f} | "
          f"{med('peak')/2**20:.0f} | {st('orient'):.2f} | {st('unsigned'):.2f} | {st('scanlines'):.2f} | {st('sign'):.2f} |")
walls = sorted(v[0] for v in per_run.values())
print(f"| **bone + {len(rows)-1} teeth** | | | **{statistics.median(walls):.1f}** ({', '.join(f'{w:.1f}' for w in walls)}) | "
      f"**{statistics.median(v[1] for v in per_run.values()):.1f}** | **{statistics.median(v[2] for v in per_run.values())/2**20:.0f}** "
      f"(largest process) | | | | |")
PY
