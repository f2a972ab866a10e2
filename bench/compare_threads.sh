#!/usr/bin/env bash
# Wall time of the demo's model comparison (scripts/demo.sh: lattice, EDFM and Biot-Stoll on the
# shipped field data under the medium-sand site prior) on 1 thread, 2 threads and the default
# (--threads 0: every usable core), pinned to CPUs 0 and 1, RUNS times each, the variants
# alternating so that a change in the machine's load falls on all of them alike. Prints each
# variant's median, its ratio to 1 thread, and whether every output (compare.json without its
# wall-time fields, every CSV and gnuplot script) is identical to the 1-thread run's; then the
# machine's load (uptime), since other work on the two cores slows every variant.
# Usage (repository root, after building): bench/compare_threads.sh [RUNS=5] [SEDWAVE=build/bin/sedwave]
set -euo pipefail
RUNS="${1:-5}"
SEDWAVE="${2:-build/bin/sedwave}"
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT
VARIANTS=("1" "2" "0")

run_once() {  # THREADS RUN -> seconds on stdout
  local dir="$OUT/t$1_r$2" code=0 start end
  start=$(date +%s.%N)
  taskset -c 0,1 "$SEDWAVE" compare data/field/zhou2009_regression.csv --models lattice,edfm,biot-stoll \
    --site data/sites/medium_sand.toml --threads "$1" --out "$dir" > "$dir.log" 2>&1 || code=$?
  end=$(date +%s.%N)
  if [ "$code" -ne 0 ] && [ "$code" -ne 3 ]; then
    echo "sedwave compare --threads $1 failed (exit $code):" >&2; cat "$dir.log" >&2; exit 1
  fi
  python3 -c 'import sys; print(float(sys.argv[2]) - float(sys.argv[1]))' "$start" "$end"
}

# The outputs that must not depend on the thread count, wall times removed.
fingerprint() {  # DIR
  (cd "$1" && jq 'walk(if type == "object" then del(.wall_seconds) else . end)' compare.json &&
    cat ./*.csv ./*.gp) | sha256sum | cut -d' ' -f1
}

declare -A times
load_before=$(uptime | sed 's/.*load/load/')
for run in $(seq 1 "$RUNS"); do
  for t in "${VARIANTS[@]}"; do
    times[$t]+="$(run_once "$t" "$run") "
  done
done

reference=$(fingerprint "$OUT/t1_r1")
median() { python3 -c 'import statistics, sys; print(f"{statistics.median(map(float, sys.argv[1:])):.2f}")' "$@"; }
base=$(median ${times[1]})
printf "%-22s | %8s | %8s | %-36s | %s\n" "sedwave compare" "median s" "ratio" "runs [s]" "outputs as 1 thread"
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
echo "runs alternate 1, 2, default, pinned with taskset -c 0,1; $(nproc) usable cores; $load_before before, $(uptime | sed 's/.*load/load/') after"
