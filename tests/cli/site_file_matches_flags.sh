#!/usr/bin/env bash
# One site given as a site file and as the command line's site options sets the same parameters: the
# two fill one typed Site and one conversion (sedwave/inversion/site.hpp) turns it into values, so
# kappa (Hertz at depth, with the water's density) and every other fixed value agree to the last bit.
#   site_file_matches_flags.sh SEDWAVE OBSERVATIONS SITE_FILE OUTDIR
# The site file is data/sites/medium_sand.toml: phi 1.75, porosity 0.40, 1 m deep, water 15 deg C, 35 ppt.
# Both for a frame with pore water (saturated-lattice) and for the dry frame (lattice), which has no
# porosity or water parameters yet takes both into Hertz at depth.
set -euo pipefail
sedwave="$1"; obs="$2"; site="$3"; out="$4"
rm -rf "$out"; mkdir -p "$out"
run() {  # MODEL DIR, then the site's options
  local model="$1" dir="$2" code=0; shift 2
  "$sedwave" invert "$obs" --model "$model" --fit gamma --method ceres --no-profile --no-plot \
    --out "$dir" "$@" > "$dir.log" 2>&1 || code=$?
  [ "$code" -eq 0 ] || [ "$code" -eq 3 ] || { echo "FAILED: invert $* exited $code"; cat "$dir.log"; exit 1; }
}
for model in saturated-lattice lattice; do
run "$model" "$out/$model-file" --site "$site"
run "$model" "$out/$model-flags" --phi 1.75 --porosity 0.40 --depth 1 --water-temperature 15 --salinity 35
python3 - "$out/$model-file/fit.json" "$out/$model-flags/fit.json" "$model" <<'PY'
import json, sys
file, flags = (json.load(open(p))["parameters"] for p in sys.argv[1:3])
fixed = [name for name, p in file.items() if not p["free"]]
differ = [f"{n}: {file[n]['value']!r} (file) vs {flags[n]['value']!r} (flags)" for n in fixed
          if file[n]["value"] != flags[n]["value"]]
if differ:
    sys.exit(f"FAILED ({sys.argv[3]}): the site file and the flags set different values:\n  " + "\n  ".join(differ))
if file["kappa"]["value"] == 6000.0:
    sys.exit(f"FAILED ({sys.argv[3]}): kappa kept the model's default: the site did not set it")
print(f"ok ({sys.argv[3]}): {len(fixed)} fixed values identical, kappa {file['kappa']['value']!r} N/m both ways")
PY
done
