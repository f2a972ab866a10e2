#!/usr/bin/env bash
# The arrival of the direct strike (`sedwave interface --direct`, example 11's scene) at the far
# edge's middle (x = 0.06 m, 0.04 m below the strike) on four meshes (h = 2, 1, 0.5, 0.25 mm), against the
# dilatational front's depth / c_L (plane stress, c_L = sqrt(E / (rho (1 - nu^2)))). Prints, per mesh,
# the run's arrival (the front: the speed reaching Ai(0)/max Ai of its first maximum) and, from the
# probe's speed history, the first time the speed reaches 10 % and 50 % of its maximum and the time
# of its first maximum. Logs stay under OUT.
#
#   bench/interface/arrival_mesh.sh [SEDWAVE [OUT]]
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
SEDWAVE=$(realpath "${1:-$ROOT/build/bin/sedwave}")
OUT=${2:-${TMPDIR:-/tmp}/sedwave-bench-interface-arrival}
mkdir -p "$OUT" && cd "$OUT"
SCENE=$ROOT/examples/11-granular-plate/scene.toml
printf '%8s %10s %10s %10s %12s %12s\n' "h mm" "front us" "10% us" "50% us" "1st max us" "depth/c_L us"
for n in 60 120 240 480; do
  sed -e "s/^elements_x = 120 .*/elements_x = $n/" -e "s/^elements_y = 40$/elements_y = $((n / 3))/" \
      -e "s/^duration = .*/duration = 1.6e-5/" -e "s/^output_interval = .*/output_interval = 1e-8/" \
      -e "s/^snapshots = .*/snapshots = 1/" "$SCENE" > direct_$n.toml
  rm -rf csv_$n
  "$SEDWAVE" interface direct_$n.toml --direct --out direct_$n.h5 --csv csv_$n > direct_$n.log
  front=$(sed -n 's/probe at x = 0.06 m.*arrival \(\S*\) s/\1/p' direct_$n.log)
  python3 - "csv_$n/probes.csv" "$n" "$front" <<'PY'
import csv, math, sys
lines = open(sys.argv[1]).read().splitlines()
head = lines[1].lstrip('# ').split(',')  # time_s,x=...,x=...
col = min(range(1, len(head)), key=lambda i: abs(float(head[i].split('=')[1]) - 0.06))
data = [[float(x) for x in r] for r in csv.reader(l for l in lines if not l.startswith('#'))]
t, v = [r[0] for r in data], [r[col] for r in data]
peak = max(v)
k_first = next(k for k in range(len(v) - 1) if v[k] >= 0.5 * peak and v[k] >= v[k + 1])
def crossing(level):
    for k in range(1, len(v)):
        if v[k] >= level:
            return t[k - 1] + (t[k] - t[k - 1]) * (level - v[k - 1]) / (v[k] - v[k - 1])
E, nu, rho = 70e9, 0.33, 2700.0
c_l = math.sqrt(E / (rho * (1 - nu * nu)))
print('%8.3g %10.4f %10.4f %10.4f %12.4f %12.4f' % (120.0 / int(sys.argv[2]), 1e6 * float(sys.argv[3]),
      1e6 * crossing(0.1 * peak), 1e6 * crossing(0.5 * peak), 1e6 * t[k_first], 1e6 * 0.04 / c_l))
PY
done
