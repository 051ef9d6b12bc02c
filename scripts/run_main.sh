#!/usr/bin/env bash
# Fresh Debian 12: install the dependencies, build the driver (Release, in build/), then run the
# default study: the two-fold e-cone at h = 0.04 traced from the flat disc to the mid-surface
# contact (examples/scenes/cone_h004.json), with its results.json, branch, events and figure
# written to out/cone_h004/. Run again, it resumes the recorded study instead of overwriting it.
# Extra arguments go to `growshell run`.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup_debian.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DGROWSHELL_BUILD_EXAMPLES=ON -DGROWSHELL_UNITY_BUILD=ON
cmake --build build -j"$(nproc)" --target growshell_driver
out=out/cone_h004
resume=()
if [ -e "$out/record.json" ]; then resume=(--resume); fi
exec build/programs/growshell run examples/scenes/cone_h004.json --out "$out" "${resume[@]}" "$@"
