#!/usr/bin/env bash
# Times `jawmesh eval` (report.json + report.html with distances to the input) and prints Markdown:
# wall and CPU seconds (median of RUNS), the report's own seconds (after reading), peak resident memory, mesh and input
# sizes, and the load average.
# Usage: bench/eval.sh <mesh.msh> <case>/input/<jaw> [path/to/jawmesh] [runs]
# Default mesh/input: the 2-tooth phantom run in ../scratch/ph2run against ../scratch/ph2.
# Environment: THREADS (default 0 = all cores).
source "$(dirname "$0")/common.sh"
mesh="${1:-$here/../../scratch/ph2run/mandible/volumetric_meshes/mandible.msh}"
input="${2:-$here/../../scratch/ph2/input/mandible}"
jawmesh="${3:-$here/../build/cli/jawmesh}"
runs="${4:-3}"
require_jawmesh "$jawmesh"
[ -f "$mesh" ] || { echo "no mesh at $mesh" >&2; exit 1; }
require_folder "$input" "input folder"
require_time
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

for run in $(seq 1 "$runs"); do
  /usr/bin/time -f "%e %M %U %S" -o "$out/time$run" "$jawmesh" --quiet --threads "$threads" eval "$mesh" --input "$input" -o "$out/report$run"
done

python3 - "$out" "$runs" "$mesh" "$input" "$(nproc)" "$(cut -d' ' -f1-3 /proc/loadavg)" <<'PY'
import json, statistics, sys
out, runs, mesh, inp, cores, load = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5], sys.argv[6]
walls, peaks, evals, cpus = [], [], [], []
for r in range(1, runs + 1):
    wall, kb, user, sys_ = open(f"{out}/time{r}").read().split()
    walls.append(float(wall)); peaks.append(int(kb) / 1024); cpus.append(float(user) + float(sys_))
    rep = json.load(open(f"{out}/report{r}/report.json"))
    evals.append(rep["seconds"])
s = rep["sizes"]
inp_tris = s["bone"].get("input_triangles", 0) + s["tooth"].get("input_triangles", 0)
print(f"`jawmesh eval` {mesh} against {inp}: {rep['mesh']['tets']:,} tets, {rep['mesh']['nodes']:,} nodes; "
      f"input {inp_tris:,} triangles (bone {s['bone'].get('input_triangles', 0):,}); {cores} cores, load {load}")
print(f"| wall s (median of {runs}) | CPU s (user+sys) | evaluation s (report.json) | peak MB | wall of each run |")
print("|---|---|---|---|---|")
print(f"| {statistics.median(walls):.2f} | {statistics.median(cpus):.2f} | {statistics.median(evals):.2f} | {max(peaks):.0f} | "
      + " / ".join(f"{w:.2f}" for w in walls) + " |")
print("verdict:", rep["verdict"]["line"])
PY
