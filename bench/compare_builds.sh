#!/usr/bin/env bash
# Wall time of the demo's model comparison (scripts/demo.sh's `sedwave compare`: lattice, EDFM and
# Biot-Stoll on the shipped field data under the medium-sand site prior, with the plots) by two
# builds of sedwave, RUNS times each, the two alternating so that a change in the machine's load
# falls on both alike. Prints each build's median wall time, the ratio, each model's evaluations
# and evidence method from compare.json, then the machine's load (uptime).
# Usage (repository root): bench/compare_builds.sh OLD_SEDWAVE NEW_SEDWAVE [RUNS=5]
#   MODELS  the models compared (default the demo's lattice,edfm,biot-stoll)
#   DATA    the observations (default the demo's data/field/zhou2009_regression.csv)
#   SITE    the site file (default the demo's data/sites/medium_sand.toml; empty: the default priors)
set -euo pipefail
OLD="$1"
NEW="$2"
RUNS="${3:-5}"
MODELS="${MODELS:-lattice,edfm,biot-stoll}"
DATA="${DATA:-data/field/zhou2009_regression.csv}"
SITE="${SITE-data/sites/medium_sand.toml}"
SITE_OPTION=()
[ -n "$SITE" ] && SITE_OPTION=(--site "$SITE")
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT

run_once() {  # BUILD NAME RUN -> seconds on stdout
  local dir="$OUT/$2_r$3" code=0 start end
  start=$(date +%s.%N)
  "$1" compare "$DATA" --models "$MODELS" "${SITE_OPTION[@]}" --out "$dir" > "$dir.log" 2>&1 || code=$?
  end=$(date +%s.%N)
  if [ "$code" -ne 0 ] && [ "$code" -ne 3 ]; then
    echo "$1 compare failed (exit $code):" >&2; cat "$dir.log" >&2; exit 1
  fi
  python3 -c 'import sys; print(float(sys.argv[2]) - float(sys.argv[1]))' "$start" "$end"
}

declare -A times
for run in $(seq 1 "$RUNS"); do
  for name in old new; do
    build="$OLD"; [ "$name" = new ] && build="$NEW"
    times[$name]+="$(run_once "$build" "$name" "$run") "
  done
done
for name in old new; do
  python3 - "$name" ${times[$name]} "$OUT/${name}_r1/compare.json" <<'PY'
import json, statistics, sys
name, *rest = sys.argv[1:]
values, report = [float(v) for v in rest[:-1]], rest[-1]
print(f"{name}: median {statistics.median(values):.2f} s over {len(values)} runs ({' '.join(f'{v:.2f}' for v in values)})")
for m in json.load(open(report)):
    e, w = m["evidence"], m["evidence_priors_widened_x10"]
    total = m.get("evaluations", e["evaluations"] + w["evaluations"])
    print(f"  {m['model']:<12} ln Z {e['log_evidence']:9.3f} +- {e['uncertainty']:.3f}  x10 {w['log_evidence']:9.3f}"
          f"  {e.get('method', 'parallel tempering')} / {w.get('method', 'parallel tempering')}  evaluations {total}")
PY
done
python3 - ${times[old]} -- ${times[new]} <<'PY'
import statistics, sys
args = sys.argv[1:]; i = args.index("--")
old, new = [float(v) for v in args[:i]], [float(v) for v in args[i + 1:]]
print(f"new / old: {statistics.median(new) / statistics.median(old):.3f}")
PY
uptime
