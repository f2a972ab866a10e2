#!/usr/bin/env bash
# What a still pore fluid does to alpha_hat and c_hat of a packing (docs/fluid.md, "Measured effect"):
# the linear engine on one channel stacked from a periodic 2000-grain cell, over omega_hat 1e-3 .. 1
# at GAMMA_HAT (default 10, the overdamped contacts that field attenuation asks for), four ways: dry,
# film only, drag only, both; then the local power law of alpha_hat in omega_hat.
#
#   bench/fluid/fluid_dispersion.sh [MU_HAT [GRAINS]]
#
# MU_HAT (default 5e-6: water around 0.3 mm quartz sand at 10 kPa) with roughness 1e-3 d and cut-off
# 0.05 d; GRAINS (default 250000: a 2.2e4 d column, so omega_hat = 1e-3 spans several wavelengths).
# WORK=DIR keeps the packing and tables (default: a new temporary folder); BUILD=DIR picks the build.
# Prints one table: omega_hat, then alpha_hat and c_hat for each case. Units: dimensionless
# (docs/physics.md).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${BUILD:-$root/build}
sedwave=$build/bin/sedwave
mu_hat=${1:-5e-6}
grains=${2:-250000}
gamma_hat=${GAMMA_HAT:-10}
work=${WORK:-$(mktemp -d /tmp/sedwave-fluid.XXXXXX)}
mkdir -p "$work"
echo "# work folder: $work; mu_hat $mu_hat, gamma_hat $gamma_hat, $grains grains"

"$root/bench/linear/stacked_field_scene.sh" "$grains" 1 > "$work/dry.toml"
fluid() {  # name, extra keys
  { cat "$work/dry.toml"
    printf '\n[fluid]\nviscosity = %s\nroughness = 1e-3\ncutoff = 0.05\n%s\n' "$mu_hat" "$2"
  } > "$work/$1.toml"
}
fluid film 'drag = "none"'
fluid drag 'lubrication = false'
fluid both ''
for case in dry film drag both; do
  printf 'scene = "%s.toml"\nomega_hat = { from = 1e-3, to = 1.0, points = 13 }\ngamma_hat = [%s]\n' \
      "$case" "$gamma_hat" > "$work/$case.grid.toml"
  rm -f "$work/$case.h5"
  start=$(date +%s)
  "$sedwave" table "$work/$case.grid.toml" --engine linear --packing "$work/packing.h5" --out "$work/$case.h5" --quiet
  echo "# $case: $(( $(date +%s) - start )) s"
done

for case in dry film drag both; do "$sedwave" show "$work/$case.h5" > "$work/$case.csv"; done
python3 - "$work" <<'PY'
import csv, math, sys
work = sys.argv[1]
cases = ["dry", "film", "drag", "both"]
table = {}
for case in cases:
    with open(f"{work}/{case}.csv") as f:
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]
    table[case] = {float(r["omega_hat"]): r for r in rows}
omegas = sorted(table["dry"])
print("omega_hat " + " ".join(f"{c + ' alpha_hat':>15} {c + ' c_hat':>11}" for c in cases))
for w in omegas:
    cells = []
    for c in cases:
        r = table[c][w]
        ok = r["status"] == "ok"
        cells.append(f"{float(r['alpha_hat']):15.4g} {float(r['c_hat']):11.4g}" if ok else f"{r['status']:>15} {'':>11}")
    print(f"{w:9.3g} " + " ".join(cells))
print("\nlocal power law d ln alpha_hat / d ln omega_hat between neighbouring frequencies")
print("omega_hat " + " ".join(f"{c:>8}" for c in cases))
for a, b in zip(omegas, omegas[1:]):
    cells = []
    for c in cases:
        ra, rb = table[c][a], table[c][b]
        if ra["status"] == "ok" and rb["status"] == "ok":
            cells.append(f"{math.log(float(rb['alpha_hat']) / float(ra['alpha_hat'])) / math.log(b / a):8.3f}")
        else:
            cells.append(f"{'-':>8}")
    print(f"{math.sqrt(a * b):9.3g} " + " ".join(cells))
PY
