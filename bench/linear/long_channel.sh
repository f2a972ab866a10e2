#!/usr/bin/env bash
# Long channels with the linear engine: alpha_hat and c_hat of one prepared N-grain W = 3 packing
# down to low omega_hat, beside the 1D lattice theory at the same gamma_hat. The packing is prepared
# once (affine compression, FIRE, Newton: docs/scenes.md) and reused for every frequency.
#
#   bench/linear/long_channel.sh [GRAINS] [GAMMA_HAT]      (defaults 10000, 0.1)
#   PACKING=FILE.h5 reuses (or writes) the packing there; BUILD=DIR picks the build (default build);
#   ABSORBING=F sets the absorbing layer's share of the column (default 0.3); OMEGAS="..." the
#   frequencies (default 0.01 0.02 0.05 0.1 0.2 0.5 1.0).
#
# Prints the preparation report, then one row per frequency: omega_hat, the linear engine's
# alpha_hat and c_hat with their standard errors (or "unresolved" with the reason), the solve time,
# and the lattice theory's alpha_hat and c_hat. Units: dimensionless (docs/physics.md).
set -euo pipefail
build=${BUILD:-build}
grains=${1:-10000}
gamma=${2:-0.1}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scene=$work/scene.toml
sed -e "s/^grains = .*/grains = $grains/" -e "s/^absorbing_fraction = .*/absorbing_fraction = ${ABSORBING:-0.3}/" \
  bench/linear/long_scene.toml > "$scene"
packing=${PACKING:-$work/packing.h5}
if [ ! -f "$packing" ]; then
  echo "# preparing $grains grains (written to $packing)"
  start=$(date +%s)
  "$build/bin/sedwave" forward "$scene" --out "$work/prepare.h5" --packing-out "$packing" | grep -v "^ *member\|^linear\|^contacts\|^alpha\|^written"
  echo "# preparation: $(( $(date +%s) - start )) s wall"
fi
printf "%-9s %-26s %-26s %-8s %-11s %-9s\n" omega_hat "alpha_hat (linear)" "c_hat (linear)" "solve_s" alpha_lattice c_lattice
for w in ${OMEGAS:-0.01 0.02 0.05 0.1 0.2 0.5 1.0}; do
  out=$("$build/bin/sedwave" forward "$scene" --packing "$packing" --omega-hat "$w" --gamma-hat "$gamma" \
          --out "$work/run.h5" 2>&1 || true)
  theory=$("$build/bin/sedwave" theory --model lattice --gamma-hat "$gamma" --omega-hat "$w" | tail -1)
  line=$(echo "$out" | grep "^alpha_hat" || true)
  alpha=$(echo "$line" | sed -n 's/^alpha_hat \([^ ]*\) +- \([^ ]*\).*/\1 +- \2/p')
  c=$(echo "$line" | sed -n 's/.*c_hat \([^ ]*\) +- \([^ ]*\).*/\1 +- \2/p')
  secs=$(echo "$line" | sed -n 's/.*(\([0-9.]*\) s of solving).*/\1/p')
  if [ -z "$alpha" ]; then
    alpha="unresolved"
    c=$(echo "$out" | sed -n 's/^not measured: //p' | cut -c1-60)
  fi
  printf "%-9s %-26s %-26s %-8s %-11s %-9s\n" "$w" "$alpha" "$c" "${secs:--}" \
    "$(echo "$theory" | cut -d, -f4)" "$(echo "$theory" | cut -d, -f5)"
done
