#!/usr/bin/env bash
# Read time of the shared 1.69 M-triangle mandible bone STL (median of 5 runs).
# Usage: bench/read_surface.sh [build-dir]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
data=$root/../shared/data/openmandible/input/mandible/bone/mandible.stl
"$build/bench/bench_read_surface" "$data" 5
