#!/usr/bin/env bash
# Reading a LAMMPS data file on 1 and more ranks (docs/performance.md, "DEM across ranks"): each
# rank parsing its share of the bytes (`ranges`, what `sedwave dem` does) against every rank parsing
# the whole file and keeping every P-th grain (`whole`), alternating, in one run.
#
# The file: COPIES (default 64) copies of a relaxed 15 625-grain periodic cell (`dem_bench prepare`)
# stacked along z (`dem_bench stack`): 10^6 grains, about 170 MB.
#
# Usage: bench/dem/read_data.sh [build-dir]
#   RANKS    rank counts (default "1 4"; more ranks than cores are oversubscribed)
#   REPEATS  runs of each mode and rank count (default 3)
#   WORK     where the cell and the stacked file go (default a new folder under /tmp)
# Prints a markdown table: the slowest rank's read seconds, grains per rank (min/max) and every
# rank's peak resident memory (min/median/max MB; the read's growth of it, min/max MB).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-$ROOT/build}
WORK=${WORK:-$(mktemp -d /tmp/sedwave-read.XXXXXX)}
COPIES=${COPIES:-64}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1

cmake -S "$ROOT" -B "$BUILD" -DSEDWAVE_BUILD_BENCH=ON >/dev/null
cmake --build "$BUILD" --target dem_bench >/dev/null
BENCH=$BUILD/bin/dem_bench
[[ -f $WORK/cell.data ]] || "$BENCH" prepare 15625 "$WORK/cell.data" >/dev/null
DATA=$WORK/stack_$COPIES.data
[[ -f $DATA ]] || "$BENCH" stack "$WORK/cell.data" "$COPIES" "$DATA" >/dev/null
echo "file: $DATA, $(du -m "$DATA" | cut -f1) MB"

echo "| mode | ranks | grains | read s | grains per rank (min/max) | peak MB per rank (min/median/max) | read growth MB (min/max) |"
echo "|---|---|---|---|---|---|---|"
for ((k = 0; k < ${REPEATS:-3}; k++)); do
  for ranks in ${RANKS:-1 4}; do
    for mode in ranges whole; do
      extra=()
      [[ $mode == whole ]] && extra=(whole)
      mpirun -np "$ranks" "$BENCH" read "$DATA" "${extra[@]}" | awk '{
        for (i = 1; i <= NF; i++) { split($i, kv, "="); v[kv[1]] = kv[2] }
        printf "| %s | %s | %s | %s | %s/%s | %s/%s/%s | %s/%s |\n", v["mode"], v["ranks"], v["grains"], v["read_s"],
          v["grains_per_rank_min"], v["grains_per_rank_max"], v["peak_rss_mb_min"], v["peak_rss_mb_median"],
          v["peak_rss_mb_max"], v["read_growth_mb_min"], v["read_growth_mb_max"] }'
    done
  done
done
