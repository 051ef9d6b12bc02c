#!/usr/bin/env bash
# The trace_disc runs behind docs/validation.md and the accuracy-cost table of
# docs/performance.md, then contact_profile on each, into DIR (default validation-runs/).
# Two runs at a time, one thread each (about 4 hours on 2 cores). Runs already finished
# (DIR/NAME/cost.json present) are skipped, so the script can be restarted.
#   usage: scripts/validation_runs.sh [DIR]      then: scripts/plot_validation.py DIR
set -euo pipefail
cd "$(dirname "$0")/.."
DIR=${1:-validation-runs}
BIN=${BIN:-build/examples}
mkdir -p "$DIR"
# The lattice disc (mesh.family = lattice) with grading exponents 1, 2 and 3.
for g in 1 2 3; do
  echo "{\"mesh\": {\"family\": \"lattice\", \"grading_exponent\": $g}}" > "$DIR/p$g.json"
done

run() {  # NAME SCENE OPTIONS...
  local name=$1 scene=$2; shift 2
  [ -f "$DIR/$name/cost.json" ] && return 0
  OMP_NUM_THREADS=1 "$BIN/trace_disc" "$DIR/$scene" --eigenmodes 0 --out "$DIR/$name" "$@" \
    > "$DIR/$name.log" 2>&1 || true
  OMP_NUM_THREADS=1 "$BIN/contact_profile" "$DIR/$name" --from 5.5 > "$DIR/$name.contact.txt" 2>&1 || true
}
export -f run
export DIR BIN

cat <<JOBS | xargs -P 2 -L 1 bash -c 'run "$@"' _
h04_p2_r24 p2.json --h 0.04 --rings 24 --phi-max 7.4 --through-contact 1
h04_p2_r36 p2.json --h 0.04 --rings 36 --phi-max 7.4 --through-contact 1
h04_p3_r24 p3.json --h 0.04 --rings 24 --phi-max 7.2 --through-contact 1
h04_p3_r36 p3.json --h 0.04 --rings 36 --phi-max 7.2 --through-contact 1
h04_p1_r24 p1.json --h 0.04 --rings 24 --phi-max 7.4 --through-contact 1
h04_p1_r36 p1.json --h 0.04 --rings 36 --phi-max 7.4 --through-contact 1
h02_p3_r12 p3.json --h 0.02 --rings 12 --phi-max 6.8 --through-contact 1
h02_p3_r16 p3.json --h 0.02 --rings 16 --phi-max 6.8 --through-contact 1
h02_p3_r24 p3.json --h 0.02 --rings 24 --phi-max 7.2 --through-contact 1
h02_p3_r36 p3.json --h 0.02 --rings 36 --phi-max 7.2 --through-contact 1
h02_p3_r48 p3.json --h 0.02 --rings 48 --phi-max 6.8 --through-contact 1
h02_p1_r16 p1.json --h 0.02 --rings 16 --phi-max 7.3 --through-contact 1
h02_p1_r24 p1.json --h 0.02 --rings 24 --phi-max 7.3 --through-contact 1
h02_p1_r36 p1.json --h 0.02 --rings 36 --phi-max 7.3 --through-contact 1
h02_p1_r48 p1.json --h 0.02 --rings 48 --phi-max 7.3 --through-contact 1
h01_p3_r24 p3.json --h 0.01 --rings 24 --phi-max 7.2 --through-contact 1
h01_p3_r36 p3.json --h 0.01 --rings 36 --phi-max 7.2 --through-contact 1
h005_p3_r24 p3.json --h 0.005 --rings 24 --phi-max 7.2 --through-contact 1
h005_p3_r36 p3.json --h 0.005 --rings 36 --phi-max 7.2 --through-contact 1
h005_p3_r48 p3.json --h 0.005 --rings 48 --phi-max 6.85 --through-contact 1
h002_p3_r24 p3.json --h 0.002 --rings 24 --phi-max 7.2 --through-contact 1
h002_p3_r36 p3.json --h 0.002 --rings 36 --phi-max 7.2 --through-contact 1
h001_p3_r24 p3.json --h 0.001 --rings 24 --phi-max 7.2 --through-contact 1 --tolerance 1e-4
h001_p3_r36 p3.json --h 0.001 --rings 36 --phi-max 6.85 --through-contact 1 --tolerance 1e-5 --max-tangent-angle 0.8 --min-step 1e-7 --eigenmodes 0
h001_p3_r48 p3.json --h 0.001 --rings 48 --phi-max 6.85 --through-contact 1 --tolerance 1e-5 --max-tangent-angle 0.8 --min-step 1e-7 --eigenmodes 0
mode3_h02_r24 p3.json --h 0.02 --rings 24 --mode 3 --phi-max 7.2
ring010_l16 p3.json --h 0.02 --inner-radius 0.1 --rings 16 --phi-max 7.6 --through-contact 1
ring025_l16 p3.json --h 0.02 --inner-radius 0.25 --rings 16 --phi-max 7.8 --through-contact 1
ring050_l16 p3.json --h 0.02 --inner-radius 0.5 --rings 16 --phi-max 8.5 --through-contact 1
ring010_l24 p3.json --h 0.02 --inner-radius 0.1 --rings 24 --phi-max 7.6 --through-contact 1
ring025_l24 p3.json --h 0.02 --inner-radius 0.25 --rings 24 --phi-max 7.8 --through-contact 1
ring050_l24 p3.json --h 0.02 --inner-radius 0.5 --rings 24 --phi-max 8.5 --through-contact 1
JOBS
echo "done: $DIR"
