#!/usr/bin/env bash
# The contact-free traces of the two-fold cone behind docs/validation.md, "The symmetric cone on
# a mesh with its symmetry": h = 0.04 on the rings family (the cone's symmetry) and the Gmsh
# family (no symmetry, no shared structure) at several size slopes, from flat past mid-surface
# contact, into DIR (default symmetric-cone-runs/). Two runs at a time, one thread each. Runs
# already finished (DIR/NAME/cost.json present) are skipped, so the script can be restarted.
#   usage: scripts/symmetric_cone_runs.sh [DIR]    then: scripts/summarize_cone_runs.py DIR
set -euo pipefail
cd "$(dirname "$0")/.."
DIR=${1:-symmetric-cone-runs}
BIN=${BIN:-build/examples}
PHI_MAX=${PHI_MAX:-7.6}
mkdir -p "$DIR"
for family in rings gmsh; do
  for c in 0.25 0.15 0.1 0.07; do
    echo "{\"thickness\": 0.04, \"mesh\": {\"family\": \"$family\", \"size_slope\": $c}," \
         "\"continuation\": {\"phi_max\": $PHI_MAX}}" > "$DIR/h04_${family}_c$c.json"
  done
done

run() {  # NAME
  local name=$1
  [ -f "$DIR/$name/cost.json" ] && return 0
  OMP_NUM_THREADS=1 "$BIN/trace_disc" "$DIR/$name.json" --through-contact 1 --eigenmodes 0 \
    --out "$DIR/$name" > "$DIR/$name.log" 2>&1 || true
}
export -f run
export DIR BIN

cat <<JOBS | xargs -P 2 -L 1 bash -c 'run "$@"' _
h04_rings_c0.25
h04_gmsh_c0.25
h04_rings_c0.15
h04_gmsh_c0.15
h04_rings_c0.1
h04_gmsh_c0.1
h04_rings_c0.07
h04_gmsh_c0.07
JOBS
