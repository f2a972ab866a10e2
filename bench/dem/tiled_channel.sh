#!/usr/bin/env bash
# A large channel tiled on every rank from one relaxed periodic cell, run for a few steps,
# checkpointed in pieces, and restarted on other rank counts (docs/performance.md, "DEM across
# ranks"). Not a scaling figure on a small machine: it checks that no rank holds the whole channel
# (peak memory per owned grain, every rank) and times reading the checkpoint back.
#
# Scene: the thesis physics of run_vs_lammps.sh (frictionless Hooke, Newton's third law on), a
# 15 625-grain packing relaxed periodic along z (`dem_bench prepare`) as the cell, COPIES copies
# stacked along z, the grains within 1.5 d of either end frozen into walls.
#
# Usage: bench/dem/tiled_channel.sh [build-dir]
#   COPIES          copies of the cell (default 640: 10^7 grains; 64: 10^6)
#   STEPS           steps per run (default 10; the first includes building the neighbour list)
#   WRITE_RANKS     ranks of the run that tiles, runs and checkpoints (default 2)
#   RESTART_RANKS   rank counts that restart from that checkpoint in turn, each running STEPS more
#                   and checkpointing again (default "3")
#   WORK            where the cell and checkpoints go (default a new folder under /tmp)
# Prints one table row per run. Memory: about 1 kB per grain in all (10^7 grains: 10 GB).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-$ROOT/build}
COPIES=${COPIES:-640}
STEPS=${STEPS:-10}
WRITE_RANKS=${WRITE_RANKS:-2}
RESTART_RANKS=${RESTART_RANKS:-3}
WORK=${WORK:-$(mktemp -d /tmp/sedwave-tiled.XXXXXX)}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

cmake -S "$ROOT" -B "$BUILD" -DSEDWAVE_BUILD_BENCH=ON >/dev/null
cmake --build "$BUILD" --target dem_bench >/dev/null
BENCH=$BUILD/bin/dem_bench
[[ -f $WORK/cell.data ]] || "$BENCH" prepare 15625 "$WORK/cell.data" >/dev/null
rm -f "$WORK"/channel.h5*

echo "| run | ranks | grains | steps | tile s | read s | ms/step | force ms (mean/max) | exchange ms/step (mean/max) | halo B/step | checkpoint s | peak MB per rank (min/median/max) | peak B per owned grain (min/max) |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
row() {  # run name, ranks, then the key=value line
  local name=$1 ranks=$2 line=$3
  awk -v name="$name" -v ranks="$ranks" '{
    for (i = 1; i <= NF; i++) { split($i, kv, "="); v[kv[1]] = kv[2] }
    printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s/%s/%s | %s/%s |\n", name, ranks, v["grains"],
      v["steps"], v["tile_s"], v["restore_s"], v["ms_per_step"], v["force_ms"], v["communication_ms"],
      v["halo_bytes_per_step"], v["checkpoint_s"], v["peak_rss_mb_min"], v["peak_rss_mb_median"], v["peak_rss_mb_max"],
      v["peak_bytes_per_owned_grain_min"], v["peak_bytes_per_owned_grain_max"] }' <<<"$line"
}
line=$(mpirun -np "$WRITE_RANKS" --oversubscribe "$BENCH" channel "$WORK/cell.data" "$COPIES" "$STEPS" "$WORK/channel.h5")
row "tile, run, checkpoint" "$WRITE_RANKS" "$line"
for p in $RESTART_RANKS; do
  line=$(mpirun -np "$p" --oversubscribe "$BENCH" channel "$WORK/cell.data" "$COPIES" "$STEPS" "$WORK/channel.h5" restart)
  row "restart, run, checkpoint" "$p" "$line"
done
echo "checkpoint: $(ls "$WORK"/channel.h5* | wc -l) files, $(du -ch "$WORK"/channel.h5* | tail -1 | cut -f1) (in $WORK)"
