#!/usr/bin/env bash
# The batch tests' dataset: 6 light one-tooth phantom cases (Patient_1..6, seeds 1..6) and one broken
# case (Patient_7: a copy of Patient_1 whose bone STL is cut in half). Run cases with
# tests/batch/fast_phantom.json: seconds each instead of minutes.
#   usage: make_test_dataset.sh <jawmesh binary> <dataset folder (replaced)>
set -euo pipefail
jawmesh=$1
dataset=$2
rm -rf "$dataset"
mkdir -p "$dataset"
for k in 1 2 3 4 5 6; do
  "$jawmesh" --quiet phantom "$dataset/Patient_$k" --teeth 1 --seed "$k" --triangles-scale 0.3
done
cp -r "$dataset/Patient_1" "$dataset/Patient_7"
bone="$dataset/Patient_7/input/mandible/bone/mandible.stl"
truncate -s $(( $(stat -c %s "$bone") / 2 )) "$bone"
