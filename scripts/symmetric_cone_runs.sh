#!/usr/bin/env bash
# The contact-free traces of the two-fold cone behind docs/validation.md, "The symmetric cone on
# a mesh with its symmetry": the rings family (the cone's symmetry) and the Gmsh family (no
# symmetry, no shared structure) at several size slopes, from flat past mid-surface contact,
# into DIR (default symmetric-cone-runs/). Two runs at a time, one thread each. Runs already
# finished (DIR/NAME/cost.json present) are skipped, so the script can be restarted.
#   usage: scripts/symmetric_cone_runs.sh [DIR]    then: scripts/summarize_cone_runs.py DIR
# THICKNESSES (default "0.04") and SLOPES (default "0.25 0.15 0.1 0.07") choose the runs;
# PHI_MAX (default 7.6) is where each trace stops.
set -euo pipefail
cd "$(dirname "$0")/.."
DIR=${1:-symmetric-cone-runs}
BIN=${BIN:-build/examples}
PHI_MAX=${PHI_MAX:-7.6}
THICKNESSES=${THICKNESSES:-0.04}
SLOPES=${SLOPES:-0.25 0.15 0.1 0.07}
mkdir -p "$DIR"
jobs=()
for h in $THICKNESSES; do
  for c in $SLOPES; do
    for family in rings gmsh; do
      name="h${h#0.}_${family}_c$c"
      echo "{\"thickness\": $h, \"mesh\": {\"family\": \"$family\", \"size_slope\": $c}," \
           "\"continuation\": {\"phi_max\": $PHI_MAX}}" > "$DIR/$name.json"
      jobs+=("$name")
    done
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

printf '%s\n' "${jobs[@]}" | xargs -P 2 -L 1 bash -c 'run "$@"' _
