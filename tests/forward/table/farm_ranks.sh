#!/usr/bin/env bash
# The task farm gives the same table on 1, 2 and 3 ranks, and with two ranks per point on 2 and 4
# ranks (the lattice theory stands in for the DEM: see farm_driver.cpp).
# usage: farm_ranks.sh MPIEXEC FARM_DRIVER DATA_DIR WORK_DIR
set -euo pipefail
mpiexec=$1 driver=$2 data=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
run() { local np=$1; shift; "$mpiexec" -np "$np" --oversubscribe "$driver" "$@"; }

for np in 1 2 3; do
  run "$np" "$data/farm_grid.toml" "$work/np$np.h5" --point-ms 20
done
for np in 2 4; do
  run "$np" "$data/farm_grid_pairs.toml" "$work/pairs_np$np.h5" --point-ms 20
done
for other in np2 np3 pairs_np2 pairs_np4; do
  "$driver" --compare "$work/np1.h5" "$work/$other.h5"
done
echo "farm_ranks: identical tables on 1, 2, 3 ranks and on 2, 4 ranks in pairs"
