#!/usr/bin/env bash
# Builds the 1D-theory and inversion benchmarks (Release, build-bench/) and runs them, printing the
# machine, the exact commands and a compact table of medians. Results: docs/performance.md,
# section "1D theory and inversion".
#
# Usage: bench/run_foundation_bench.sh [REPETITIONS]     (default 5)
# Environment: BUILD_DIR (default <repo>/build-bench), JOBS (default 1),
#              BENCH_FILTER (a --benchmark_filter regex for both programs, default: all).
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
reps=${1:-5}
build=${BUILD_DIR:-"$repo/build-bench"}
jobs=${JOBS:-1}
filter=${BENCH_FILTER:-.}
results="$build/bench-results"

echo "== sedwave foundation benchmarks (1D theory and inversion)"
echo "date:       $(date -u '+%Y-%m-%d %H:%M:%S UTC')"
echo "host cores: nproc=$(nproc)"
echo "cpu:        $(lscpu | grep 'Model name' | sed 's/Model name:[[:space:]]*//')"
echo "load:       $(cut -d' ' -f1-3 /proc/loadavg) (1/5/15 min, before the build)"
echo "compiler:   $(${CXX:-c++} --version | head -n1)"
echo "commit:     $(git -C "$repo" rev-parse --short HEAD 2>/dev/null || echo unknown)$(git -C "$repo" diff --quiet HEAD -- 2>/dev/null || echo ' (+ local changes)')"
echo

cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release -DSEDWAVE_BUILD_TESTS=OFF -DSEDWAVE_BUILD_BENCH=ON \
  -DSEDWAVE_WERROR=ON >/dev/null
cmake --build "$build" -j"$jobs" --target bench_theory bench_inversion >/dev/null
mkdir -p "$results"

common=(--benchmark_repetitions="$reps" --benchmark_report_aggregates_only=true --benchmark_filter="$filter"
        --benchmark_out_format=json)
for prog in bench_theory bench_inversion; do
  cmd=("$build/bin/$prog" "${common[@]}" --benchmark_out="$results/$prog.json")
  echo "\$ ${cmd[*]}"
  "${cmd[@]}" >"$results/$prog.txt" 2>&1 || { cat "$results/$prog.txt"; exit 1; }
done
echo

if ! command -v python3 >/dev/null; then
  echo "(python3 not found: full outputs in $results/*.txt)"
  cat "$results"/bench_theory.txt "$results"/bench_inversion.txt
  exit 0
fi
python3 - "$results/bench_theory.json" "$results/bench_inversion.json" <<'EOF'
import json, sys

for path in sys.argv[1:]:
    with open(path) as f:
        doc = json.load(f)
    rows = {}
    for b in doc["benchmarks"]:
        if b.get("run_type") != "aggregate":
            continue
        name = b["run_name"].removesuffix("/real_time")
        row = rows.setdefault(name, {"unit": b.get("time_unit", "ns")})
        row[b["aggregate_name"]] = b
    print(f"{path.rsplit('/', 1)[-1]}  ({doc['context'].get('num_cpus')} cpus, "
          f"{doc['context'].get('mhz_per_cpu')} MHz, library_build_type={doc['context'].get('library_build_type')})")
    print(f"  {'benchmark':<38} {'wall med':>9} {'cpu med':>9} {'unit':<4} {'cv wall':>7}  {'reps':>4}  extra")
    for name, row in rows.items():
        med = row.get("median")
        if med is None:
            continue
        cv = row.get("cv", {}).get("real_time")
        extra = ""
        if "chi2" in med:
            extra = f"chi2={med['chi2']:.6g} converged={int(med['converged'])} nlopt_evals={int(med['nlopt_evals'])}"
        cv_text = f"{100 * cv:6.1f}%" if cv is not None else "    n/a"
        print(f"  {name:<38} {med['real_time']:>9.4g} {med['cpu_time']:>9.4g} {row['unit']:<4} {cv_text}  "
              f"{med['repetitions']:>4}  {extra}")
    print()
print("wall med = median elapsed time; cpu med = median CPU time of the process. When other work")
print("shares the cores, wall > cpu: the benchmark was waiting for a core, not computing.")
EOF
echo "full outputs: $results/{bench_theory,bench_inversion}.{txt,json}"
