#!/usr/bin/env bash
# The main job on a fresh Debian machine (as root): install what is missing, build Release,
# invert the shipped field data (Zhou et al. 2009 regressions) with the lattice chain model, then
# rank the dry chain against Biot-Stoll and EDFM by evidence under a medium-sand site prior.
# Extra arguments go to `sedwave invert` (e.g. --model continuum --method ceres).
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
sedwave_install_packages
cmake -S "$SEDWAVE_ROOT" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD_DIR" -j "$JOBS" --target sedwave
sedwave_install_python
OUT="${OUT:-$SEDWAVE_ROOT/out/demo}"
status=0
"$BUILD_DIR/bin/sedwave" invert "$SEDWAVE_ROOT/data/field/zhou2009_regression.csv" \
  --model lattice --fit kappa,d,gamma --method global --out "$OUT" "$@" || status=$?
# Exit code 3: the fit ran and wrote its report, and flagged some result (WARNING above). On these
# data the dry-frame chain needs contacts stiffer than Hertz: that flag is the demo's finding.
if [ "$status" -ne 0 ] && [ "$status" -ne 3 ]; then exit "$status"; fi
[ "$status" -eq 3 ] && echo "demo: the fit finished; sedwave flagged the results listed under WARNING (exit code 3, docs/cli.md)"

compare_status=0
"$BUILD_DIR/bin/sedwave" compare "$SEDWAVE_ROOT/data/field/zhou2009_regression.csv" \
  --models lattice,edfm,biot-stoll --site "$SEDWAVE_ROOT/data/sites/medium_sand.toml" \
  --out "$OUT/compare" || compare_status=$?
if [ "$compare_status" -eq 3 ]; then
  echo "demo: the comparison finished, but a sampler did not converge (see NOT CONVERGED above)"
elif [ "$compare_status" -ne 0 ]; then
  exit "$compare_status"
fi
exit 0
