#!/usr/bin/env bash
# Fresh Debian 12: install the dependencies, build the examples (Release, in build/), then trace
# the default e-cone into out/econe/. Extra arguments go to econe_at.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup_debian.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DGROWSHELL_BUILD_EXAMPLES=ON
cmake --build build -j"$(nproc)" --target growshell_examples
mkdir -p out/econe
exec build/examples/econe_at --out out/econe "$@"
