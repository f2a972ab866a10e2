#!/usr/bin/env bash
# Task-farm efficiency of `sedwave table`: the same 6-point table (bench/table_farm_grid.toml, the
# small table's scene, N = 1000) on 1, 2 and 3 ranks, all from one prepared packing, so only the
# farm and the points are timed. Prints wall time per point, speed-up and efficiency against 1 rank,
# and the machine load (other jobs on the machine distort everything; note it with the numbers).
#
# usage: bench/table_farm.sh [BUILD_DIR]   (default build; needs BUILD_DIR/bin/sedwave)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
sedwave=$build/bin/sedwave
work=$build/bench-table-farm
grid=$root/bench/table_farm_grid.toml
packing=$root/data/tables/thesis_w3_small.packing.h5
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mkdir -p "$work"
[ -f "$packing" ] || { echo "no packing $packing: see data/tables/README.md" >&2; exit 1; }
echo "cores: $(nproc); load before: $(uptime | sed 's/.*load average: //')"

points=6
printf "%-5s %10s %14s %9s %11s %s\n" ranks "wall [s]" "wall/point [s]" speed-up efficiency "ranks busy (farm)"
for np in 1 2 3; do
  rm -f "$work/np$np.h5" "$work/np$np.h5.journal"
  start=$(date +%s.%N)
  summary=$(mpirun -np "$np" --oversubscribe "$sedwave" table "$grid" --out "$work/np$np.h5" --packing "$packing" \
            --quiet | tail -1)
  wall=$(echo "$(date +%s.%N) - $start" | bc -l)
  [ "$np" = 1 ] && wall1=$wall
  busy=$(echo "$summary" | sed -n 's/.*ranks busy \([0-9]*\) %.*/\1/p')
  printf "%-5s %10.1f %14.2f %9.2f %10.0f%% %s%%\n" "$np" "$wall" "$(echo "$wall / $points" | bc -l)" \
    "$(echo "$wall1 / $wall" | bc -l)" "$(echo "100 * $wall1 / ($wall * $np)" | bc -l)" "$busy"
done
echo "load after: $(uptime | sed 's/.*load average: //')"
