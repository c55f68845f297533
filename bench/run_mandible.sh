#!/usr/bin/env bash
# The whole pipeline (`jawmesh run`) on the shared OpenMandible mandible, RUNS times (default 3, at
# least 3 for a median). Prints Markdown: the median wall time, CPU time and peak resident memory
# of the process, then the median seconds of every stage from run.json, and the mesh figures of
# the last run. Keeps the last run's output in OUT (default: a temporary folder, removed).
# Usage: bench/run_mandible.sh [path/to/jawmesh] [runs]
# Environment: JAWMESH_DATA (default: ../shared/data beside the checkout), THREADS (default 0 = all),
#              OUT (keep the last run there).
source "$(dirname "$0")/common.sh"
jawmesh="${1:-$here/../build/cli/jawmesh}"
runs="${2:-3}"
require_jawmesh "$jawmesh"
require_mandible_case case_dir
require_runs "$runs"
require_time
make_work_dir work
for run in $(seq 1 "$runs"); do
  rm -rf "$work/out"
  /usr/bin/time -f '{"wall": %e, "cpu": %U, "sys": %S, "max_rss_kb": %M}' -o "$work/time$run.json" \
    "$jawmesh" --quiet --threads "$threads" run "$case_dir" -o "$work/out" --jaw mandible
  cp "$work/out/mandible/run.json" "$work/run$run.json"
done
python3 - "$work" "$runs" "$(nproc)" "$(cut -d' ' -f1-3 /proc/loadavg)" <<'PY'
import json, statistics, sys
work, runs, cores, load = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
times = [json.load(open(f"{work}/time{i}.json")) for i in range(1, runs + 1)]
recs = [json.load(open(f"{work}/run{i}.json")) for i in range(1, runs + 1)]
med = statistics.median
print(f"`jawmesh run` OpenMandible mandible, median of {runs} runs, {cores} cores, load at the end {load}:\n")
print("| wall s | CPU s | peak MB |")
print("|---:|---:|---:|")
print(f"| {med(t['wall'] for t in times):.0f} | {med(t['cpu'] + t['sys'] for t in times):.0f} | "
      f"{med(t['max_rss_kb'] for t in times) / 1024:.0f} |")
print("\n| stage | median s |")
print("|---|---:|")
for i, st in enumerate(recs[0]["stages"]):
    print(f"| {st['name']} | {med(r['stages'][i]['seconds'] for r in recs):.1f} |")
last = recs[-1]
print(f"\nmesh: {last['mesh']}, quality: {last['quality']}, "
      f"surface triangles per kind: {last['surface']['simplify']['triangles_per_kind']}")
PY
if [ -n "${OUT:-}" ]; then rm -rf "$OUT"; mv "$work/out" "$OUT"; fi
