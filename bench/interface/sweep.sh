#!/usr/bin/env bash
# The sweeps of docs/interface.md ("Findings"), on example 11's scene (200 beads, 300 us).
#
# 1. Shock energy: struck at 0.03, 0.1, 0.3, 1 and 3 m/s (four decades of input energy), frictionless,
#    with friction and rotation, and with friction but no rotation; the arrival at the plate's far edge
#    against that of a direct strike on the plate's edge with the same energy (`--direct`; the plate
#    is linear, so one direct run serves every energy).
# 2. The dimensionless groups apart: the bead modulus, the plate modulus, k_s and the speed varied
#    independently (three materials x two speeds x frictionless and three k_s), so that runs share
#    Pi_H with different k_s v and the reverse.
#
# Every row: the groups, Pi_H = (3/2) k_gp delta^(1/2) / (E_p t) = 2 E*_gp a / (E_p t) (the grain-plate
# Hertz tangent stiffness at the peak overlap of one bead striking the plate's edge, held rigid, at the
# strike speed, over the plate's in-plane stiffness; 1/E*_gp = (1-nu_b^2)/E_b + (1-nu_p^2)/E_p, a the
# contact radius) and k_s v; the arrival at the far edge's middle; the largest share of the input in
# the plate; the share transmitted (in the plate or absorbed by its edges) at the end; friction's
# share; and the participation ratio of the grains' energy at the end (how many of the 200 grains
# share it). Then that ratio over time at 1 m/s, frictionless and with friction (the runs' energies.csv).
# Logs and runs stay under OUT.
#
#   bench/interface/sweep.sh [SEDWAVE [OUT]]
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
SEDWAVE=$(realpath "${1:-$ROOT/build/bin/sedwave}")
OUT=${2:-${TMPDIR:-/tmp}/sedwave-bench-interface-sweep}
mkdir -p "$OUT" && cd "$OUT"
SCENE=$ROOT/examples/11-granular-plate/scene.toml

# NAME FRICTION ROTATION K_S BEAD_MODULUS PLATE_MODULUS [DURATION] (example 11: 0.3 true 100 200e9 70e9 3e-4)
variant() {
  sed -e "s/^duration = 3e-4$/duration = ${7:-3e-4}/" -e "s/^friction = 0.3$/friction = $2/" -e "s/^rotation = true$/rotation = $3/" \
      -e "s/^tanh_velocity_scale = 100 /tanh_velocity_scale = $4 /" \
      -e "s/^youngs_modulus = 200e9$/youngs_modulus = $5/" -e "s/^youngs_modulus = 70e9$/youngs_modulus = $6/" \
      "$SCENE" > "$1.toml"
}

# One run: NAME SPEED; prints its row.
row() {
  local log=$1_$2.log
  "$SEDWAVE" interface "$1.toml" --speed "$2" --out "$1_$2.h5" --csv "$1_$2_csv" > "$log"
  python3 - "$1.toml" "$log" "$2" "$1" "${direct:-nan}" <<'PY'
import math, re, sys, tomllib
scene = tomllib.load(open(sys.argv[1], "rb"))
log, v, name, direct = open(sys.argv[2]).read(), float(sys.argv[3]), sys.argv[4], float(sys.argv[5])
num = lambda pattern: float(re.search(pattern, log).group(1))
b, p, c = scene["packing"], scene["plate"], scene["contact"]
Eb, nub, Ep, nup, r, t = b["youngs_modulus"], b["poisson_ratio"], p["youngs_modulus"], p["poisson_ratio"], b["radius"], p["thickness"]
m = 4 / 3 * math.pi * r**3 * b["density"]
e_star = 1 / ((1 - nub**2) / Eb + (1 - nup**2) / Ep)          # grain-plate, the interpolated contact
delta = (15 * m * v**2 / (16 * e_star * math.sqrt(r))) ** 0.4  # Johnson 11.23, R* = r, the edge held
pi_hertz = 2 * e_star * math.sqrt(r * delta) / (Ep * t)
ks = c["tanh_velocity_scale"] if c["friction"] > 0 else 0.0
arrival = num(r"x = 0\.06 m, y = -0\.04 m: arrival (\S+) s")
plate_max = num(r"largest share in the plate (\S+);")
absorbed = num(r"absorbed by the plate's edges (\S+) of it")
plate_end = num(r", plate (\S+), friction")
friction = num(r", friction (\S+), dashpots")
shared = num(r"energy is shared by (\S+) of")
delay = f"{arrival / direct:6.1f}" if math.isfinite(direct) else f"{'-':>6s}"
print(f"{name:22s} {Eb / 1e9:5.4g} {Ep / 1e9:5.4g} {v:5g} {ks:6g} {pi_hertz:8.3g} {ks * v:6g} {arrival * 1e6:8.1f} "
      f"{delay} {plate_max:9.4f} {absorbed + plate_end:9.4f} {friction:9.4f} {shared:7.1f}")
PY
}
header() {
  printf '%-22s %5s %5s %5s %6s %8s %6s %8s %6s %9s %9s %9s %7s\n' run "E_b" "E_p" "v" "k_s" "Pi_H" "k_s v" \
    "arr us" "delay" "plate max" "transmit" "friction" "shared"
}

# 1. Shock energy.
variant frictionless 0.0 true 100 200e9 70e9
variant friction 0.3 true 100 200e9 70e9
variant friction_no_rotation 0.3 false 100 200e9 70e9
# The direct pulse is as short as the mesh allows: sampled every 10 ns over the first 20 us.
sed -e "s/^duration = .*/duration = 2e-5/" -e "s/^output_interval = .*/output_interval = 1e-8/" "$SCENE" > direct.toml
"$SEDWAVE" interface direct.toml --direct --out direct.h5 > direct.log
direct=$(sed -n 's/probe at x = 0.06 m.*arrival \(\S*\) s/\1/p' direct.log)
echo "direct strike: arrival $direct s at the far edge's middle (moduli in GPa, speeds in m/s, k_s in s/m)"
header
for name in frictionless friction friction_no_rotation; do
  for v in 0.03 0.1 0.3 1 3; do row $name $v; done
done

# 2. The groups apart: soft beads (E_b = 21.7 GPa) and a stiff plate (E_p = 362 GPa) at 1 m/s have
# example 11's Pi_H at 0.1 m/s; k_s = 10, 100, 1000 s/m at 0.1 and 1 m/s cross k_s v = 10 and 100.
# The soft beads' Hertz times are (200/21.7)^(2/5) = 2.4 times longer: they run 750 us, not 300.
echo
direct=nan
header
for material in "steel_al 200e9 70e9 3e-4" "soft_beads 21.7e9 70e9 7.5e-4" "stiff_plate 200e9 362e9 3e-4"; do
  set -- $material
  variant "$1_frictionless" 0.0 true 100 "$2" "$3" "$4"
  for v in 0.1 1; do row "$1_frictionless" $v; done
  for ks in 10 100 1000; do
    variant "$1_ks$ks" 0.3 true $ks "$2" "$3" "$4"
    for v in 0.1 1; do row "$1_ks$ks" $v; done
  done
done

# 3. How localised the grains' energy stays: the participation ratio over time at 1 m/s.
echo
echo "participation ratio of the grains' energy (of 200 grains) at 1 m/s"
python3 - frictionless_1_csv/energies.csv friction_1_csv/energies.csv <<'PY'
import csv, sys
runs = {}
for path in sys.argv[1:]:
    rows = [r for r in csv.reader(open(path)) if r and not r[0].startswith("#")]
    runs[path.split("_1_csv")[0]] = {round(float(r[0]) * 1e6, 3): float(r[-1]) for r in rows}
times = [0, 10, 25, 50, 75, 100, 150, 200, 300]
print(f"{'t us':22s}" + "".join(f"{t:7d}" for t in times))
for name, p in runs.items():
    print(f"{name:22s}" + "".join(f"{p[float(t)]:7.1f}" for t in times))
PY
