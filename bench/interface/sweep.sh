#!/usr/bin/env bash
# The shock-energy sweep of docs/interface.md ("Findings"): example 11's scene struck at 0.03, 0.1,
# 0.3, 1 and 3 m/s (four decades of input energy), frictionless, with friction and rotation, and with
# friction but no rotation. Prints one row per run: the dimensionless groups (Hertz tangent stiffness
# at the first collision's peak over the plate's E t; k_s v), the arrival at the plate's far edge
# against that of a direct strike on the plate's edge with the same energy (`--direct`; the plate is
# linear, so one direct run serves every energy), the largest share of the input
# in the plate, the share transmitted (in the plate or absorbed by its edges) at the end, friction's
# share, and the kinetic energy left in the three rows at the free end. Logs stay under OUT.
#
#   bench/interface/sweep.sh [SEDWAVE [OUT]]
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
SEDWAVE=$(realpath "${1:-$ROOT/build/bin/sedwave}")
OUT=${2:-${TMPDIR:-/tmp}/sedwave-bench-interface-sweep}
mkdir -p "$OUT" && cd "$OUT"
SCENE=$ROOT/examples/11-granular-plate/scene.toml

variant() {  # NAME FRICTION ROTATION
  sed -e "s/^friction = 0.3$/friction = $2/" -e "s/^rotation = true$/rotation = $3/" "$SCENE" > "$1.toml"
}
variant frictionless 0.0 true
variant friction 0.3 true
variant friction_no_rotation 0.3 false

# The direct pulse is as short as the mesh allows: sampled every 10 ns over the first 20 us.
sed -e "s/^duration = .*/duration = 2e-5/" -e "s/^output_interval = .*/output_interval = 1e-8/" "$SCENE" > direct.toml
"$SEDWAVE" interface direct.toml --direct --out direct.h5 > direct.log
direct=$(sed -n 's/probe at x = 0.06 m.*arrival \(\S*\) s/\1/p' direct.log)
echo "direct strike: arrival $direct s at the far edge's middle"
printf '%-22s %6s %10s %8s %11s %9s %9s %9s %9s %9s\n' variant "v m/s" "Pi_hertz" "k_s v" "arrival us" "delay" \
  "plate max" "transmit" "friction" "near hit"
for name in frictionless friction friction_no_rotation; do
  for v in 0.03 0.1 0.3 1 3; do
    log=${name}_$v.log
    "$SEDWAVE" interface $name.toml --speed $v --out ${name}_$v.h5 > "$log"
    python3 - "$log" "$v" "$name" "$direct" <<'PY'
import math, re, sys
log, v, name, direct = open(sys.argv[1]).read(), float(sys.argv[2]), sys.argv[3], float(sys.argv[4])
num = lambda pattern: float(re.search(pattern, log).group(1))
E, nu, rho, r = 200e9, 0.3, 7850.0, 2.5e-3          # steel beads
Ep, nup, rhop, t, depth = 70e9, 0.33, 2700.0, 5e-3, 0.04  # aluminium plate
m = 4 / 3 * math.pi * r**3 * rho
e_star = E / (2 * (1 - nu**2)); m_star = m / 2; r_star = r / 2
k = 4 / 3 * e_star * math.sqrt(r_star)
delta = (15 * m_star * v**2 / (16 * e_star * math.sqrt(r_star))) ** 0.4   # Johnson 11.23
pi_hertz = 1.5 * k * math.sqrt(delta) / (Ep * t)
ks = 100.0 if name != "frictionless" else 0.0
c_l = math.sqrt(Ep / (rhop * (1 - nup**2)))
arrival = num(r"x = 0\.06 m, y = -0\.04 m: arrival (\S+) s")
plate_max = num(r"largest share in the plate (\S+);")
absorbed = num(r"absorbed by the plate's edges (\S+) of it")
plate_end = num(r", plate (\S+), friction")
friction = num(r", friction (\S+), dashpots")
near = num(r"three rows at the free end: (\S+) of the input")
print(f"{name:22s} {v:6g} {pi_hertz:10.3g} {ks * v:8.3g} {arrival * 1e6:11.1f} {arrival / direct:9.1f} "
      f"{plate_max:9.4f} {absorbed + plate_end:9.4f} {friction:9.4f} {near:9.4f}")
PY
  done
done
