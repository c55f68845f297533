#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, AddressSanitizer + UndefinedBehaviorSanitizer) in build-fuzz/
# and runs each for a bounded time, starting from its seed corpus (tests/fuzz/corpus/<target>/) and
# the inputs that once crashed it (tests/fuzz/regressions/<target>/).
#   bash tests/fuzz/run_fuzzers.sh [seconds per target, default 30] [target ...]
# A crash, a hang (> 10 s on one input), a leak or an invalid result fails the script; the input is
# in build-fuzz/crashes/<target>/. Fix the reader, then copy the input to
# tests/fuzz/regressions/<target>/: the normal tests replay it (tests/io/test_fuzz_inputs.cpp).
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds="${1:-30}"
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(stl_binary stl_ascii obj ply off axes_json config_json nrrd nifti labels_json edits_json)

flags="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
generator=""; [ -f build-fuzz/CMakeCache.txt ] || generator="-GNinja"
CC=clang CXX=clang++ cmake $generator -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DJAWMESH_FUZZ=ON \
  -DJAWMESH_BUILD_TESTS=OFF -DJAWMESH_UNITY_BUILD=ON -DCMAKE_CXX_FLAGS="$flags" > /dev/null
cmake --build build-fuzz --target jawmesh_fuzzers -j "$(nproc)"

failed=()
for t in "${targets[@]}"; do
  work="build-fuzz/corpus/$t"
  crashes="build-fuzz/crashes/$t"
  mkdir -p "$work" "$crashes"
  seeds=("tests/fuzz/corpus/$t")
  [ -d "tests/fuzz/regressions/$t" ] && seeds+=("tests/fuzz/regressions/$t")
  echo "== fuzz_$t for ${seconds} s"
  # New inputs go to the first folder (the build's working corpus); the repository's are read only.
  if ! UBSAN_OPTIONS=print_stacktrace=1 LSAN_OPTIONS=suppressions="$PWD/tests/lsan.supp" ./build-fuzz/tests/fuzz/fuzz_"$t" "$work" "${seeds[@]}" \
      -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=4096 \
      -artifact_prefix="$crashes/" -print_final_stats=1 > "build-fuzz/fuzz_$t.log" 2>&1; then
    failed+=("$t")
    tail -n 40 "build-fuzz/fuzz_$t.log"
  fi
  grep -E "^stat::number_of_executed_units|^Done [0-9]+ runs" "build-fuzz/fuzz_$t.log" | tail -n 1 || true
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzzers failed: ${failed[*]} (inputs in build-fuzz/crashes/)" >&2
  exit 1
fi
echo "fuzzers: no crash in ${#targets[@]} targets x ${seconds} s"
