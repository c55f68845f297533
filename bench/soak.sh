#!/usr/bin/env bash
# The soak bench of issue #27: how often a run is lost. Writes generated cases (bench_soak: phantom
# seeds x tooth counts x dirty variants), runs them all with `jawmesh batch` (in parallel, as a
# cohort is run; resumable: run it again to finish), then prints one Markdown row per variant:
# cases, meshed (valid, no tet under 10 deg), meshed with tets under 10 deg, refused with a message
# naming the input, and failures (the tet stage or anything else; their surfaces stay in
# <out>/<case>/mandible/failed_surface/).
# Usage: bench/soak.sh <work dir> [bench_soak keys: seeds=4 teeth=1,4,8,14 variants=... scale=0.25]
# JAWMESH (default build/cli/jawmesh), BENCH_SOAK (default build/bench/bench_soak), JOBS (batch --jobs).
source "$(dirname "$0")/common.sh"
[ $# -ge 1 ] || { echo "usage: $0 <work dir> [seeds=N teeth=a,b variants=x,y scale=s]" >&2; exit 2; }
work="$1"
shift
jawmesh="${JAWMESH:-$here/../build/cli/jawmesh}"
soak="${BENCH_SOAK:-$here/../build/bench/bench_soak}"
require_jawmesh "$jawmesh"
require_jawmesh "$soak"
require_python3
[ -d "$work/dataset" ] || "$soak" "$work/dataset" "$@"
start=$(date +%s)
"$jawmesh" --threads "$threads" -q batch "$work/dataset" -o "$work/out" --jobs "${JOBS:-0}" || true  # failures are counted below
echo "batch: $(( $(date +%s) - start )) s wall" >&2
python3 - "$work/out" <<'EOF'
import csv, json, os, sys, collections
out = sys.argv[1]
rows = collections.defaultdict(lambda: collections.Counter())
failures = []
for r in csv.DictReader(open(os.path.join(out, "summary.csv"))):
    variant = r["case"].split("-")[0]
    rows[variant]["cases"] += 1
    if r["status"] == "ok":
        record = json.load(open(os.path.join(out, r["case"], r["jaw"], "run.json")))
        below = record["quality"]["tets_below_min_dihedral"]
        rows[variant]["meshed" if below == 0 else "meshed, tets under 10 deg"] += 1
    elif r["status"] == "failed":
        error = r["error"]
        tet = "tetrahedralize" in error or "failed_surface" in error
        rows[variant]["failed (tet stage)" if tet else "refused or failed elsewhere"] += 1
        failures.append((r["case"], error[:160]))
    else:
        rows[variant][r["status"]] += 1
keys = ["cases", "meshed", "meshed, tets under 10 deg", "refused or failed elsewhere", "failed (tet stage)"]
print("| variant | " + " | ".join(keys) + " |")
print("|---" * (len(keys) + 1) + "|")
total = collections.Counter()
for v in sorted(rows):
    total.update(rows[v])
    print("| " + v + " | " + " | ".join(str(rows[v][k]) for k in keys) + " |")
print("| all | " + " | ".join(str(total[k]) for k in keys) + " |")
for case, error in failures:
    print(f"- {case}: {error}")
EOF
