#!/usr/bin/env bash
# The linear engine against the time-domain DEM at equal error, at low frequency (OMEGA_HAT, default
# 0.05; GAMMA_HAT, default 1; docs/linear.md, "Speed at equal error"). Both engines drive the same
# packing; the DEM runs until echoes could return (the wave must cross the column), the linear engine solves
# once. At equal error the ratio of their times is the speedup: the error of one packing is its
# disorder, the same for both (the two agree on the same packing; the script prints both).
#
#   bench/linear/equal_error.sh [GRAINS...]     (default: 30000)
#
# GRAINS = 10000 takes the shipped field packing #0 (prepared directly, column 900 d; DEM 20 s at
# gamma_hat = 1, 2 min at 0.1, on one core); any other size is a channel stacked from a periodic
# 2000-grain cell (seed 1; docs/linear.md, "Channels of 10^5 to 10^6 grains"), prepared here in
# seconds. The DEM's cost grows as N^2 (grains x steps to cross the column): N = 3*10^4 takes 3 min
# at gamma_hat = 1, 15 min at 0.1 (where the automatic time step is 6x shorter). BUILD=DIR picks the
# build (default build); WORK=DIR keeps the packings (default: a temporary folder).
# At gamma_hat = 0.1 the DEM's lock-in windows on a stacked channel are not yet steady (its cells
# ring for longer than the run), so the two engines differ there by more than their errors.
# Units: dimensionless (docs/physics.md).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${BUILD:-$root/build}
work=${WORK:-$(mktemp -d /tmp/sedwave-equal-error.XXXXXX)}
mkdir -p "$work"
echo "# work folder: $work; load: $(uptime | sed 's/.*load average/load average/')"
for grains in "${@:-30000}"; do
  if [ "$grains" = 10000 ]; then
    packing=$root/data/tables/field_w3.packing.h5
  else
    packing=$work/stacked$grains.h5
    if [ ! -f "$packing" ]; then
      "$root/bench/linear/stacked_field_scene.sh" "$grains" 1 > "$work/stacked$grains.toml"
      "$build/bin/sedwave" forward "$work/stacked$grains.toml" --out "$work/prepare$grains.h5" \
          --packing-out "$packing" | grep "^tiled\|column height"
    fi
  fi
  echo "# N = $grains: $packing"
  "$build/bin/bench_speed_vs_error" --omega-hat "${OMEGA_HAT:-0.05}" --gamma-hat "${GAMMA_HAT:-1}" --dem 0 "$packing" |
      grep -v "^#   omega"
done
