#!/usr/bin/env bash
# The runs behind docs/performance.md, "Accuracy against cost of the cone study": the default
# cone study (examples/scenes/cone_h004.json, h = 0.04, flat -> 7.6 through contact) with one
# knob changed at a time, each a `growshell sweep` into DIR/<knob>, one thread per run, two
# chains of sweeps side by side on the 2 cores; then the table and figure.
#   usage: scripts/accuracy_cost_runs.sh [DIR]   (default out/results/accuracy_cost; ~20 min)
# A sweep already finished is resumed (nothing to do); delete its directory to run it again.
set -euo pipefail
cd "$(dirname "$0")/.."
DIR=${1:-out/results/accuracy_cost}
BIN=${BIN:-build/programs/growshell}
SCENE=examples/scenes/cone_h004.json
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
mkdir -p "$DIR"
sweep() {  # NAME --param KEY=VALUES
  local name=$1; shift
  local resume=()
  if [ -e "$DIR/$name/sweep_plan.json" ]; then resume=(--resume); fi
  # A point that ends early (e.g. the core floor h/8 at 4.54) makes the sweep exit 3: its
  # row says so, and the other sweeps go on.
  "$BIN" sweep "$SCENE" --out "$DIR/$name" "$@" "${resume[@]}" > "$DIR/$name.log" 2>&1 ||
    echo "accuracy_cost_runs.sh: sweep $name exited with $? (see $DIR/$name/sweep.csv)"
}
(
  sweep mesh_size --param mesh.size_slope=0.14,0.1,0.07,0.05
  sweep tolerance --param study.tolerance=1e-5,1e-7
  sweep max_step --param continuation.max_step=0.2,0.05
) &
chain=$!
sweep quadrature --param mesh.quadrature_degree=1,3
sweep core_floor --param mesh.min_spacing=0.02,0.005
sweep corrector --param continuation.corrector=chord
sweep quadrature_high --param mesh.quadrature_degree=4,6
wait "$chain"
/usr/bin/python3 scripts/plot_accuracy_cost.py "$DIR/accuracy_cost" \
    --reference "$DIR/mesh_size/point_003" --default "$DIR/mesh_size/point_001" \
    --size-sweep "$DIR/mesh_size" \
    "$DIR/mesh_size" "$DIR/tolerance" "$DIR/max_step" "$DIR/quadrature" "$DIR/quadrature_high" \
    "$DIR/core_floor" "$DIR/corrector"
