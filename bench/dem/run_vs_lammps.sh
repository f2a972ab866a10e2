#!/usr/bin/env bash
# sedwave DEM engine vs LAMMPS on the thesis scene, measured in the same run.
#
# Scene: frictionless Hooke spheres, d = 1 +- 0.2 (uniform), density 1, E = 1000, nu = 2/7 (LAMMPS
# example-script kn, kt = 2/7 kn unused), e_n = 0.9 (gamma_n for the lightest pair), dt = 0.01 t_col,
# skin 0.1, W = 3 periodic channel (periodic along z too), compressed packing prepared by sedwave
# and handed to both codes as the same LAMMPS data file (with the same small random velocities).
# LAMMPS runs pair gran/hooke (xmu = 0), fix nve/sphere (bench/dem/in.thesis.lmp). Both codes run with the same newton
# setting: NEWTON=on (default; each pair across a periodic face or rank boundary computed once, the
# reaction sent back) or NEWTON=off (computed on both sides, the thesis's LAMMPS setting).
#
# Usage: bench/dem/run_vs_lammps.sh [build-dir]   (SIZES="2000 10000" to choose sizes, NEWTON=off)
# Prints a markdown table: ns per grain-step for both codes on 1 and 2 ranks, the ratio, the
# parallel efficiency and sedwave's memory per grain.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-$ROOT/build-dem}
WORK=${WORK:-$(mktemp -d /tmp/sedwave-dem-bench.XXXXXX)}
SIZES=${SIZES:-"2000 10000 50000"}
NEWTON=${NEWTON:-on}
export DEM_BENCH_NEWTON=$NEWTON
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

command -v lmp >/dev/null || { apt-get install -y lammps >/dev/null; }
cmake -S "$ROOT" -B "$BUILD" -DSEDWAVE_BUILD_BENCH=ON >/dev/null
cmake --build "$BUILD" -j1 --target dem_bench >/dev/null
cp "$BUILD/bin/dem_bench" "$WORK/dem_bench"

read -r KN GAMMA_N DT < <("$WORK/dem_bench" params)
# Long enough (1.4-1.7 s of sedwave on one rank) that a host hiccup of tens of ms does not decide
# the ratio.
steps_for() { case $1 in 2000) echo 20000 ;; 10000) echo 4000 ;; *) echo 1000 ;; esac; }

lammps_ns() {  # data file, steps, ranks, grains -> ns per grain-step
  local data=$1 steps=$2 ranks=$3 n=$4
  mpirun -np "$ranks" --oversubscribe lmp -in "$ROOT/bench/dem/in.thesis.lmp" -log none -screen "$WORK/lmp.out" \
    -var data "$data" -var kn "$KN" -var gamma_n "$GAMMA_N" -var dt "$DT" -var newton "$NEWTON" \
    -var warm $(( steps / 10 < 200 ? steps / 10 : 200 )) -var steps "$steps" >/dev/null
  awk -v n="$n" '/^Loop time/ {t=$4; s=$9} END {printf "%.2f", 1e9*t/(n*s)}' "$WORK/lmp.out"
}

echo "newton $NEWTON; load before: $(uptime | sed 's/.*load average/load average/')"
echo
echo "| N | steps | sedwave 1 rank | LAMMPS 1 rank | ratio | sedwave 2 ranks | LAMMPS 2 ranks | ratio | sedwave 2-rank efficiency | sedwave bytes/grain (engine) | (RSS growth) |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for N in $SIZES; do
  data="$WORK/packing_$N.data"
  "$WORK/dem_bench" prepare "$N" "$data" >/dev/null
  steps=$(steps_for "$N")
  line1=$(mpirun -np 1 "$WORK/dem_bench" run "$data" "$steps")
  line2=$(mpirun -np 2 --oversubscribe "$WORK/dem_bench" run "$data" "$steps")
  s1=$(sed -E 's/.*ns_per_grain_step=([0-9.]+).*/\1/' <<<"$line1")
  s2=$(sed -E 's/.*ns_per_grain_step=([0-9.]+).*/\1/' <<<"$line2")
  mem=$(sed -E 's/.*engine_bytes_per_grain=([0-9.]+).*/\1/' <<<"$line1")
  rss=$(sed -E 's/.*rss_growth_bytes_per_grain=([0-9.]+).*/\1/' <<<"$line1")
  l1=$(lammps_ns "$data" "$steps" 1 "$N")
  l2=$(lammps_ns "$data" "$steps" 2 "$N")
  awk -v n="$N" -v st="$steps" -v s1="$s1" -v l1="$l1" -v s2="$s2" -v l2="$l2" -v m="$mem" -v r="$rss" 'BEGIN {
    printf "| %d | %d | %.1f | %.1f | %.2f | %.1f | %.1f | %.2f | %.0f %% | %.0f | %.0f |\n",
      n, st, s1, l1, s1 / l1, s2, l2, s2 / l2, 100 * s1 / (2 * s2), m, r }'
done
