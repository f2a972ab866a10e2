#!/usr/bin/env bash
# The linear engine against the time-domain DEM on the same five packings at three frequencies
# (issue: frequency-domain steady state vs time-domain lock-in). Prepares the packings once (kept
# in WORK_DIR, reused on a second run), then prints bench_linear_vs_dem's table.
# usage: bench/linear/linear_vs_dem.sh [BUILD_DIR] [WORK_DIR]     (about 15 min on one core)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../../build}
work=${2:-/tmp/sedwave_linear_vs_dem}
mkdir -p "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
if [ ! -f "$work/packing.member4.h5" ]; then
  "$build/bin/sedwave" forward "$here/compare_scene.toml" --out "$work/linear.h5" --packing-out "$work/packing.h5" --quiet
fi
packings=("$work/packing.h5")
for k in 1 2 3 4; do packings+=("$work/packing.member$k.h5"); done
"$build/bin/bench_linear_vs_dem" --gamma-hat 0.1 --amplitude 1e-4 --absorbing-fraction 0.45 --omega-hat 0.3 --omega-hat 0.6 --omega-hat 1.0 \
  "${packings[@]}"
