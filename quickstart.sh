#!/usr/bin/env bash
# jawmesh quick start. Run as root on Debian 12 (or with sudo available):
#   bash quickstart.sh demo   install dependencies, build, mesh the synthetic jaw phantom -> out/demo
#   bash quickstart.sh test   install dependencies, build, run every test (quick set, then slow set)
#   bash quickstart.sh slurm-test   also install Slurm + munge, build, run the batch on a real
#                                   single-node Slurm started on localhost (tests/slurm/)
#   bash quickstart.sh robustness   also install clang; build with AddressSanitizer + UBSan in
#                                   build-asan/ and run the quick tests there (long end-to-end runs
#                                   excluded, see SANITIZE_EXCLUDE); run every libFuzzer target for
#                                   FUZZ_SECONDS (default 30) each (tests/fuzz/run_fuzzers.sh)
set -euo pipefail
cd "$(dirname "$0")"

PACKAGES=(cmake make ninja-build g++ pkg-config
  libopenvdb-dev libboost-iostreams-dev libboost-system-dev libtbb-dev libembree-dev libtet1.5-dev
  libeigen3-dev libcli11-dev nlohmann-json3-dev libgtest-dev zlib1g-dev libteem-dev libnifti2-dev)
# Only for the tests: meshio reads our volume files back, CalculiX solves the decks, Chromium renders
# the report. The demo needs none of them (session 17: it ran on a machine without them).
TEST_PACKAGES=(python3-meshio calculix-ccx chromium)
# Only for `slurm-test`: a real single-node Slurm on localhost.
SLURM_PACKAGES=(slurmctld slurmd slurm-client munge python3)
# Only for `robustness`: clang with its libFuzzer runtime, and the symbolizer for readable reports.
ROBUSTNESS_PACKAGES=(clang libclang-rt-14-dev llvm)
# Quick tests left out of the sanitizer run: end-to-end pipeline runs that take minutes in the
# Release build and 5-10x longer under ASan (the phantom runs at default options, from surfaces
# and from label volumes, the batches, the dirty-surface runs, the editing example and the what-if
# runs at 0.1 mm; the what-ifs run sanitized in RunEdits.Batch* at 0.2 mm). The
# determinism test stays: two small runs of the whole pipeline (level sets, carving, surface,
# TetGen, evaluation, FE decks) under the sanitizers.
SANITIZE_EXCLUDE="RunPhantom|RunLabelMap|BatchCommand|BadInput.DirtySurfacesAreMeshed|EditLevelSetsExample|RunEdits.WhatIfs|RunEdits.EditOnACarvedFolder|RunImplant"

install_packages() {
  local missing=()
  for p in "${PACKAGES[@]}" "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return
  echo "Installing: ${missing[*]}"
  local sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# A new build tree is configured for Ninja, which compiles a target's files while the libraries it
# links are still being built (Make waits for them: one core idles at the end of every library);
# an existing tree keeps its generator.
generator_for() { [ -f "$1/CMakeCache.txt" ] || echo "-GNinja"; }

# build [target...]: the Release tree in build/, all of it or only the targets named. Unity builds
# (CMakeLists.txt): a fresh build takes about half the CPU.
build() {
  cmake $(generator_for build) -S . -B build -DCMAKE_BUILD_TYPE=Release -DJAWMESH_UNITY_BUILD=ON > /dev/null
  cmake --build build -j "$(nproc)" ${1:+--target "$@"}
}

# Sanitizer build: -O1 keeps it fast to build and to run; debug line tables for the reports. Only
# the binary and the quick test executables whose own sources are light (no slow_* suites, no
# benchmarks): test_levelset and test_filters compile OpenVDB into most of their files and run the
# longest under ASan (about 35 of the step's 85 CPU minutes), and the code they test runs under the
# sanitizers anyway through the binary's runs (determinism, bad input, eval, interrupt tests).
# `SANITIZE_ALL=1 bash quickstart.sh robustness` builds and runs every quick test executable.
SANITIZE_TARGETS=(jawmesh test_core test_io test_tet test_fe test_batch test_cli)
[ -n "${SANITIZE_ALL:-}" ] && SANITIZE_TARGETS+=(test_levelset test_filters)
sanitize_build() {
  cmake $(generator_for build-asan) -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DJAWMESH_SANITIZE=ON -DJAWMESH_UNITY_BUILD=ON \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" > /dev/null
  cmake --build build-asan -j "$(nproc)" --target "${SANITIZE_TARGETS[@]}"
}

case "${1:-}" in
  demo)
    install_packages
    build jawmesh  # the binary only: the test executables are most of a full build
    ./build/cli/jawmesh demo -o out/demo
    echo "Outputs in out/demo"
    ;;
  test)
    install_packages "${TEST_PACKAGES[@]}"
    build
    ctest --test-dir build -L quick --output-on-failure --timeout 1200 -j "$(nproc)"
    ctest --test-dir build -L slow --output-on-failure --timeout 1200 -j "$(nproc)"
    ;;
  mandible-test)
    # The whole pipeline on the shared mandible (about 3 minutes on 2 cores), then the tests that check a
    # finished run (tests/cli/slow_run_mandible.cpp, SlowEval, the interface surface
    # against the run's label field) and the mandible given as a label volume
    # (tests/cli/slow_label_map_mandible.cpp, another 5 minutes), and the what-ifs of issue #24
    # (tests/cli/slow_edit_mandible.cpp); not part of CI's time.
    install_packages "${TEST_PACKAGES[@]}"
    build
    [ -d ../shared/data/openmandible ] || { echo "no ../shared/data/openmandible" >&2; exit 1; }
    rm -rf build/mandible-run
    ./build/cli/jawmesh run ../shared/data/openmandible -o build/mandible-run --jaw mandible --write-levelsets
    # The what-ifs of issue #24 on the carved grids of that run, meshed (another 3 minutes).
    rm -rf build/mandible-edit build/mandible-edit-run
    ./build/cli/jawmesh edit build/mandible-run/mandible/levelsets --edits tests/data/mandible_what_if.json \
      -o build/mandible-edit
    ./build/cli/jawmesh run ../shared/data/openmandible --from-vdb build/mandible-edit -o build/mandible-edit-run \
      --jaw mandible
    # The shared maxilla's interface surface, checked the same way (another 3 minutes).
    rm -rf build/maxilla-run
    [ -d ../shared/data/p26-maxilla-teeth ] &&
      ./build/cli/jawmesh run ../shared/data/p26-maxilla-teeth -o build/maxilla-run --jaw maxilla --write-levelsets
    JAWMESH_MANDIBLE_RUN="$PWD/build/mandible-run/mandible" JAWMESH_LABEL_MAP_TEST=1 \
      JAWMESH_MANDIBLE_EDIT_RUN="$PWD/build/mandible-edit-run/mandible" JAWMESH_MAXILLA_RUN="$PWD/build/maxilla-run/maxilla" \
      ctest --test-dir build -L slow -R 'SlowRunMandible|MandibleRun|SlowInterfaces|SlowLabelMap|SlowEditMandible' \
      --output-on-failure
    ;;
  slurm-test)
    install_packages "${TEST_PACKAGES[@]}" "${SLURM_PACKAGES[@]}"
    build
    bash tests/slurm/slurm_batch_test.sh build/cli/jawmesh
    ;;
  robustness)
    install_packages "${TEST_PACKAGES[@]}" "${ROBUSTNESS_PACKAGES[@]}"
    sanitize_build
    ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions="$PWD/tests/lsan.supp" UBSAN_OPTIONS=print_stacktrace=1 \
      ctest --test-dir build-asan -L quick -E "$SANITIZE_EXCLUDE" --output-on-failure --timeout 1200 -j "$(nproc)"
    bash tests/fuzz/run_fuzzers.sh "${FUZZ_SECONDS:-30}"
    ;;
  *)
    echo "usage: bash quickstart.sh demo|test|slurm-test|mandible-test|robustness" >&2
    exit 2
    ;;
esac
