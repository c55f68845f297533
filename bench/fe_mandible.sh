#!/usr/bin/env bash
# CalculiX on the tipping deck of a meshed jaw (issue #7 figures): solves a copy of <out>/<jaw> with
# `jawmesh fe --scenario tipping --format inp --solve` and prints Markdown: mesh size, wall and ccx
# seconds, peak resident memory (jawmesh or ccx, whichever is larger), per tooth the load point's
# displacement and the tooth's largest displacement (from ccx's .frd), incisors against molars, and
# the PDL element von Mises stresses (median, 99.99th percentile, their ratio; from ccx's .dat).
# Usage: bench/fe_mandible.sh <out>/<jaw> [path/to/jawmesh] [order 1|2]
# Environment: SOLVER_THREADS (default 1), KEEP=<dir> keeps the solved copy there.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
jawdir="${1:?usage: bench/fe_mandible.sh <out>/<jaw> [jawmesh] [order]}"
jawmesh="${2:-$here/../build/cli/jawmesh}"
order="${3:-1}"
threads="${SOLVER_THREADS:-1}"
jaw="$(basename "$jawdir")"
[ -x "$jawmesh" ] || { echo "no jawmesh executable at $jawmesh (build it, or pass its path)" >&2; exit 1; }
[ -f "$jawdir/volumetric_meshes/$jaw.msh" ] || { echo "no mesh at $jawdir/volumetric_meshes/$jaw.msh" >&2; exit 1; }
command -v /usr/bin/time >/dev/null || { echo "needs /usr/bin/time (Debian package time)" >&2; exit 1; }
command -v ccx >/dev/null || { echo "needs ccx (Debian package calculix-ccx)" >&2; exit 1; }
if [ -n "${KEEP:-}" ]; then work="$KEEP"; mkdir -p "$work"; else work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT; fi
copy="$work/$jaw"
mkdir -p "$copy/volumetric_meshes"
cp "$jawdir/volumetric_meshes/$jaw.msh" "$copy/volumetric_meshes/"

/usr/bin/time -f "%e %M" -o "$work/time" "$jawmesh" --quiet fe "$copy" --scenario tipping --format inp \
  --order "$order" --solve --solver-threads "$threads" > "$work/summary.json"

python3 - "$work" "$copy" "$jawdir" "$order" "$threads" "$(nproc)" "$(cut -d' ' -f1-3 /proc/loadavg)" <<'PY'
import json, sys
work, copy, jawdir, order, threads, cores, load = sys.argv[1:8]
wall, kb = open(f"{work}/time").read().split()
s = json.load(open(f"{copy}/simulation/tipping_calculix_summary.json"))
elements = sum(r["elements"] for r in s["regions"].values())
print(f"`jawmesh fe {jawdir} --scenario tipping --format inp --order {order} --solve`: {elements:,} C3D{'4' if order == '1' else '10'} "
      f"elements, {s['status']}; ccx {s['seconds']:.1f} s ({threads} thread), wall {float(wall):.1f} s, peak {int(kb) / 1024:.0f} MB; "
      f"{cores} cores, load {load}")
print()
print("| tooth | load point displacement mm | along the force mm | tooth's largest displacement mm |")
print("|---|---|---|---|")
teeth = {t["unn"]: t for t in s["teeth"]}
for unn, t in sorted(teeth.items()):
    print(f"| {unn} | {t['magnitude_mm']:.4g} | {t['along_force_mm']:.4g} | {t['tooth_max_displacement_mm']:.4g} |")
inc = [teeth[u]["tooth_max_displacement_mm"] for u in (23, 24, 25, 26) if u in teeth]
mol = [teeth[u]["tooth_max_displacement_mm"] for u in (18, 19, 30, 31) if u in teeth]
if inc and mol:
    print(f"\nincisors (23-26) least {min(inc):.4g} mm, molars (18, 19, 30, 31) most {max(mol):.4g} mm: "
          f"incisors move more: {min(inc) > max(mol)}")
allmax = [t["tooth_max_displacement_mm"] for t in teeth.values()]
print(f"largest tooth displacements {min(allmax):.3g} .. {max(allmax):.3g} mm (issue: within 1e-4 .. 1e-1)")
p = s["pdl"]
print(f"PDL von Mises over {p['elements']:,} elements: median {p['median_von_mises_mpa']:.4g} MPa, 99.99th percentile "
      f"{p['p9999_von_mises_mpa']:.4g} MPa ({p['p9999_over_median']:.2f}x median; issue: under 20x), max {p['max_von_mises_mpa']:.4g} MPa")
PY
