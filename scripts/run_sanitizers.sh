#!/usr/bin/env bash
# The library under AddressSanitizer and UndefinedBehaviorSanitizer (clang, the `fuzz` preset
# with tests, in build-fuzz/): the fast unit tests of the layers that read input and evaluate
# the shell (core, io, mesh, subdivision, energy, assembly, studies without the orientation
# check's relaxations), then each libFuzzer target for FUZZ_SECONDS (default 30) from its seed
# corpus in fuzz/corpus/. Any sanitizer report, leak, failed test, crash or hang fails it.
# Run by scripts/run_tests.sh (so by CI); docs/verification.md, "Sanitizers and fuzzing in CI".
set -euo pipefail
cd "$(dirname "$0")/.."

fuzz_seconds="${FUZZ_SECONDS:-30}"
cmake --preset fuzz -DGROWSHELL_BUILD_TESTS=ON >/dev/null
tests=(tests_core tests_io tests_mesh tests_subdivision tests_energy tests_assembly tests_studies)
fuzzers=(fuzz_scene_parser fuzz_saved_state fuzz_mesh_readers)
cmake --build build-fuzz -j"$(nproc)" --target "${tests[@]}" "${fuzzers[@]}"

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
for t in "${tests[@]}"; do
  filter="*"
  # The orientation check relaxes whole cones: minutes under the sanitizers, and the same code
  # as the relaxations the other layers' tests run.
  [[ $t == tests_studies ]] && filter="-PatternOrientationCheck.*"
  echo "run_sanitizers.sh: $t"
  "build-fuzz/tests/$t" --gtest_brief=1 --gtest_filter="$filter"
done

declare -A corpus=([fuzz_scene_parser]=scene [fuzz_saved_state]=state [fuzz_mesh_readers]=mesh)
for f in "${fuzzers[@]}"; do
  found="build-fuzz/fuzz-found/$f"
  mkdir -p "$found"
  echo "run_sanitizers.sh: $f for ${fuzz_seconds} s"
  # The first directory collects new inputs (kept out of the source tree); the second holds
  # the seeds. A crash, a leak, a sanitizer report or an input slower than 10 s fails.
  log="build-fuzz/fuzz-found/$f.log"
  if ! "build-fuzz/fuzz/$f" -max_total_time="$fuzz_seconds" -timeout=10 -rss_limit_mb=2048 \
      -print_final_stats=1 "$found" "fuzz/corpus/${corpus[$f]}" >"$log" 2>&1; then
    cat "$log"
    echo "run_sanitizers.sh: $f failed (the input is in build-fuzz/ as crash-*, leak-*, timeout-*)" >&2
    exit 1
  fi
  grep -E "^Done|stat::(number_of_executed_units|new_units_added|peak_rss_mb)" "$log"
done
echo "run_sanitizers.sh: all passed"
