#!/usr/bin/env bash
# Wall time of the demo's model comparison (scripts/demo.sh: lattice, EDFM and Biot-Stoll on the
# shipped field data under the medium-sand site prior) on 1 thread, 2 threads and the default
# (--threads 0: every usable core), pinned to CPUs 0 and 1, RUNS times each, the variants
# alternating so that a change in the machine's load falls on all of them alike. Prints each
# variant's median, its ratio to 1 thread, and whether every output (compare.json without its
# wall-time fields, every CSV and gnuplot script) is identical to the 1-thread run's; then the
# machine's load (uptime), since other work on the two cores slows every variant.
# Usage (repository root, after building): bench/compare_threads.sh [RUNS=5] [SEDWAVE=build/bin/sedwave]
#   CPUS     the CPUs to pin to (taskset -c; default 0,1)
#   THREADS  the --threads values to alternate (default "1 2 0"; the first is the reference)
#   MODELS   the models compared (default the demo's lattice,edfm,biot-stoll; all six on a many-core
#            machine: lattice,saturated-lattice,biot-stoll,edfm,grain-shearing,vgs-lambda)
set -euo pipefail
RUNS="${1:-5}"
SEDWAVE="${2:-build/bin/sedwave}"
CPUS="${CPUS:-0,1}"
MODELS="${MODELS:-lattice,edfm,biot-stoll}"
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT
read -r -a VARIANTS <<<"${THREADS:-1 2 0}"

run_once() {  # THREADS RUN -> seconds on stdout
  local dir="$OUT/t$1_r$2" code=0 start end
  start=$(date +%s.%N)
  taskset -c "$CPUS" "$SEDWAVE" compare data/field/zhou2009_regression.csv --models "$MODELS" \
    --site data/sites/medium_sand.toml --threads "$1" --out "$dir" > "$dir.log" 2>&1 || code=$?
  end=$(date +%s.%N)
  if [ "$code" -ne 0 ] && [ "$code" -ne 3 ]; then
    echo "sedwave compare --threads $1 failed (exit $code):" >&2; cat "$dir.log" >&2; exit 1
  fi
  python3 -c 'import sys; print(float(sys.argv[2]) - float(sys.argv[1]))' "$start" "$end"
}

# The outputs that must not depend on the thread count, wall times removed (Python rather than jq,
# which a bare many-core machine may lack).
fingerprint() {  # DIR
  (cd "$1" && python3 -c '
import json, sys
def strip(x):
    if isinstance(x, dict):
        return {k: strip(v) for k, v in x.items() if k != "wall_seconds"}
    return [strip(v) for v in x] if isinstance(x, list) else x
print(json.dumps(strip(json.load(open("compare.json"))), sort_keys=True))' && cat ./*.csv ./*.gp) |
    sha256sum | cut -d' ' -f1
}

declare -A times
load_before=$(uptime | sed 's/.*load/load/')
for run in $(seq 1 "$RUNS"); do
  for t in "${VARIANTS[@]}"; do
    times[$t]+="$(run_once "$t" "$run") "
  done
done

reference=$(fingerprint "$OUT/t${VARIANTS[0]}_r1")
median() { python3 -c 'import statistics, sys; print(f"{statistics.median(map(float, sys.argv[1:])):.2f}")' "$@"; }
base=$(median ${times[${VARIANTS[0]}]})
printf "%-22s | %8s | %8s | %-36s | %s\n" "sedwave compare" "median s" "ratio" "runs [s]" "outputs as --threads ${VARIANTS[0]}"
for t in "${VARIANTS[@]}"; do
  identical=yes
  for run in $(seq 1 "$RUNS"); do
    [ "$(fingerprint "$OUT/t${t}_r$run")" = "$reference" ] || identical=NO
  done
  m=$(median ${times[$t]})
  label="--threads $t"; [ "$t" = 0 ] && label="--threads 0 (default)"
  printf "%-22s | %8s | %8.2f | %-36s | %s\n" "$label" "$m" "$(python3 -c "print($m / $base)")" \
    "$(printf '%.2f ' ${times[$t]})" "$identical"
done
echo "models $MODELS; runs alternate --threads ${VARIANTS[*]}, pinned with taskset -c $CPUS; $(nproc) usable cores; $load_before before, $(uptime | sed 's/.*load/load/') after"
