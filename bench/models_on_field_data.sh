#!/bin/sh
# Every sediment model fitted to the shipped field data (data/field/zhou2009_regression.csv: points
# sampled from the Zhou, Zhang & Knobles 2009 regressions, 50-1000 Hz), one table row per fit:
# reduced chi^2, the fitted values, kappa over the Hertz stiffness where the model has contacts,
# and the plausibility flags. Quoted in docs/models/README.md.
# Usage (repository root, after building): sh bench/models_on_field_data.sh [build/bin/sedwave]
set -eu
SEDWAVE="${1:-build/bin/sedwave}"
DATA=data/field/zhou2009_regression.csv
LW=data/tables/field_w3_long_wavelength.h5
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT

row() {  # NAME then invert options
  name="$1"; shift
  code=0
  "$SEDWAVE" invert "$DATA" --no-plot --out "$OUT/$name" "$@" > "$OUT/$name.log" 2>&1 || code=$?
  if [ "$code" -ne 0 ] && [ "$code" -ne 3 ]; then
    echo "$name: sedwave invert failed (exit $code):"; cat "$OUT/$name.log"; exit 1
  fi
  python3 - "$OUT/$name/fit.json" "$name" "$*" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
def shown(p):
    v = p["value"]
    if not p.get("free"):
        return None
    if p.get("identifiable"):
        return f"{p['name']} {v:.3g}±{p['sigma']:.2g}"
    return f"{p['name']} not determined"
params = []
for name, p in j["parameters"].items():
    p = dict(p, name=name)
    s = shown(p)
    if s: params.append(s)
combos = {c: j["combinations"][c]["value"] for c in j.get("combinations", {})}
kh = f"{combos['kappa_over_hertz']:.3g}" if "kappa_over_hertz" in combos else "-"
flags = "; ".join(f["quantity"] for f in j.get("flags", [])) or "-"
print(f"| {sys.argv[2]} | `{sys.argv[3]}` | {j['reduced_chi2']:.3g} | {', '.join(params)} | {kh} | {flags} |")
PY
}

echo "| fit | options | χ²/ν | fitted (1σ) | κ/κ_Hertz | flags |"
echo "|---|---|---|---|---|---|"
row lattice --model lattice
row long-wavelength-table --model "table:$LW" --fit kappa,gamma --d 3e-4
row saturated-lattice --model saturated-lattice --fit kappa,gamma --d 3e-4 --set porosity=0.38
row saturated-lattice-044 --model saturated-lattice --fit kappa,gamma,permeability --d 3e-4 --set porosity=0.44
row saturated-lattice-free --model saturated-lattice --fit kappa,gamma,porosity,permeability --d 3e-4
row saturated-table --model "saturated-table:$LW" --fit kappa,gamma,porosity,permeability --d 3e-4
row edfm --model edfm --fit porosity,permeability
row biot-stoll --model biot-stoll --fit porosity,permeability,delta_b
row grain-shearing --model grain-shearing --fit porosity,gamma_p,n
row vgs-lambda --model vgs-lambda --fit porosity,gamma_p,tau_p
