#!/usr/bin/env bash
# Fresh Debian 12: install the dependencies, build everything (Release, in build/), run the
# test suite. Exits non-zero on any failure.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup_debian.sh
# Benchmarks are off by default; build them here so they at least compile. A unity build
# (batches of GROWSHELL_UNITY_BATCH_SIZE files per target): a clean build in less time.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DGROWSHELL_BUILD_TESTS=ON \
  -DGROWSHELL_BUILD_BENCHMARKS=ON -DGROWSHELL_UNITY_BUILD=ON
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j2
# The fast unit tests under ASan + UBSan, and each libFuzzer target for 30 s (clang, build-fuzz/).
bash scripts/run_sanitizers.sh
