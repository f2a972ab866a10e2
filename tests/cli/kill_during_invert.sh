#!/usr/bin/env bash
# Runs `sedwave invert` once to completion, then 12 more times killed with SIGKILL after delays
# spread over a run; after each kill every output must still be a whole file (the previous run's
# or the new one's): fit.json parses, the CSVs end with a newline and have as many rows as before.
#   kill_during_invert.sh SEDWAVE OBSERVATIONS OUTDIR
set -uo pipefail
sedwave="$1"; obs="$2"; out="$3"
rm -rf "$out"
"$sedwave" invert "$obs" --no-plot --out "$out" >/dev/null
[ -s "$out/fit.json" ] || { echo "FAILED: the first run wrote no fit.json"; exit 1; }
rows_curves=$(wc -l < "$out/curves.csv"); rows_obs=$(wc -l < "$out/observations.csv")
for delay in 0.01 0.03 0.05 0.08 0.1 0.13 0.16 0.2 0.25 0.3 0.35 0.4; do
  timeout -s KILL "$delay" "$sedwave" invert "$obs" --no-plot --out "$out" >/dev/null 2>&1
  python3 -c "import json,sys; json.load(open(sys.argv[1]))" "$out/fit.json" \
    || { echo "FAILED: fit.json is not whole after a kill at ${delay} s"; exit 1; }
  [ "$(wc -l < "$out/curves.csv")" = "$rows_curves" ] || { echo "FAILED: curves.csv cut after ${delay} s"; exit 1; }
  [ "$(wc -l < "$out/observations.csv")" = "$rows_obs" ] || { echo "FAILED: observations.csv cut after ${delay} s"; exit 1; }
done
leftovers=$(ls "$out" | grep -c '\.tmp-' || true)
echo "ok: 12 kills, every output whole ($leftovers temporary files left by killed runs)"
