#!/usr/bin/env bash
# Large channels tiled on every rank from one relaxed periodic cell (docs/performance.md, "DEM
# across ranks"). Not scaling figures on a small machine.
#
# Scene: the thesis physics of run_vs_lammps.sh (frictionless Hooke, Newton's third law on), a
# 15 625-grain packing relaxed periodic along z (`dem_bench prepare`) as the cell, COPIES copies
# stacked along z, the grains within 1.5 d of either end frozen into walls.
#
# Usage: bench/dem/tiled_channel.sh restart|uneven [build-dir]
#   restart   tile, run STEPS and checkpoint on WRITE_RANKS ranks (default 2), then restart from
#             that checkpoint on each of RESTART_RANKS in turn (default "3"), each running STEPS
#             more and checkpointing again. Checks that no rank holds the whole channel (peak
#             memory per owned grain, every rank) and times reading the checkpoint back.
#             COPIES default 640 (10^7 grains, about 10 GB in all), STEPS default 10 (the first
#             step includes building the neighbour list).
#   uneven    load balance under uneven work: the upper half of the channel loses the fraction
#             LOOSE (default 0.5) of its grains (a jammed half beside a loose one); each of RANKS
#             (default "2 3 4") runs with fixed slabs and with slabs balanced on listed pairs at
#             every rebuild (lists rebuilt every REBUILD_EVERY = 20 steps). The work imbalance
#             (largest rank's listed pairs + grains over the mean, at the end) does not depend on
#             the machine; the force-loop imbalance (slowest rank's force time over the mean) does,
#             and oversubscribed it measures the scheduler as much as the work. COPIES default 8,
#             STEPS default 200.
#   WORK      where the cell and checkpoints go (default a new folder under /tmp)
#   BENCH     a dem_bench to run instead of building one (e.g. a pack's, bench/dem/pack_for_device.sh);
#             then CELL names a prepared cell (default WORK/cell.data, prepared if missing) and
#             MPIRUN the launcher (default "mpirun --oversubscribe"; a pack's needs its libraries:
#             "env LD_LIBRARY_PATH=... mpirun --bind-to core")
# Prints a markdown table.
set -euo pipefail
MODE=${1:?usage: tiled_channel.sh restart|uneven [build-dir]}
[[ $MODE == restart || $MODE == uneven ]] || { echo "tiled_channel.sh: unknown mode '$MODE' (restart or uneven)" >&2; exit 2; }
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${2:-$ROOT/build}
WORK=${WORK:-$(mktemp -d /tmp/sedwave-tiled.XXXXXX)}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

if [[ -z ${BENCH:-} ]]; then
  cmake -S "$ROOT" -B "$BUILD" -DSEDWAVE_BUILD_BENCH=ON >/dev/null
  cmake --build "$BUILD" --target dem_bench >/dev/null
  BENCH=$BUILD/bin/dem_bench
fi
read -r -a LAUNCH <<<"${MPIRUN:-mpirun --oversubscribe}"
CELL=${CELL:-$WORK/cell.data}
[[ -f $CELL ]] || "${LAUNCH[@]}" -np 1 "$BENCH" prepare 15625 "$CELL" >/dev/null

row() {  # run name, ranks, then the key=value line
  local name=$1 ranks=$2 line=$3
  awk -v name="$name" -v ranks="$ranks" '{
    for (i = 1; i <= NF; i++) { split($i, kv, "="); v[kv[1]] = kv[2] }
    printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s/%s/%s | %s/%s |\n", name, ranks, v["grains"],
      v["steps"], v["tile_s"], v["restore_s"], v["ms_per_step"], v["force_ms"], v["communication_ms"],
      v["halo_bytes_per_step"], v["checkpoint_s"], v["peak_rss_mb_min"], v["peak_rss_mb_median"], v["peak_rss_mb_max"],
      v["peak_bytes_per_owned_grain_min"], v["peak_bytes_per_owned_grain_max"] }' <<<"$line"
}

restart_table() {
  local copies=${COPIES:-640} steps=${STEPS:-10} write_ranks=${WRITE_RANKS:-2} line p
  rm -f "$WORK"/channel.h5*
  echo "| run | ranks | grains | steps | tile s | read s | ms/step | force ms (mean/max) | exchange ms/step (mean/max) | halo B/step | checkpoint s | peak MB per rank (min/median/max) | peak B per owned grain (min/max) |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  line=$("${LAUNCH[@]}" -np "$write_ranks" "$BENCH" channel "$CELL" "$copies" "$steps" "$WORK/channel.h5")
  row "tile, run, checkpoint" "$write_ranks" "$line"
  for p in ${RESTART_RANKS:-3}; do
    line=$("${LAUNCH[@]}" -np "$p" "$BENCH" channel "$CELL" "$copies" "$steps" "$WORK/channel.h5" restart)
    row "restart, run, checkpoint" "$p" "$line"
  done
  echo "checkpoint: $(ls "$WORK"/channel.h5* | wc -l) files, $(du -ch "$WORK"/channel.h5* | tail -1 | cut -f1) (in $WORK)"
}

uneven_table() {
  local copies=${COPIES:-8} steps=${STEPS:-200} ranks=${RANKS:-2 3 4} line p slabs
  export DEM_BENCH_LOOSE=${LOOSE:-0.5} DEM_BENCH_REBUILD_EVERY=${REBUILD_EVERY:-20}
  echo "| ranks | slabs | grains | work imbalance (max/mean) | force-loop imbalance (max/mean) | ms/step |"
  echo "|---|---|---|---|---|---|"
  for p in $ranks; do
    for slabs in fixed pairs; do
      line=$(DEM_BENCH_SLABS=$slabs "${LAUNCH[@]}" -np "$p" -x DEM_BENCH_SLABS -x DEM_BENCH_LOOSE \
             -x DEM_BENCH_REBUILD_EVERY "$BENCH" channel "$CELL" "$copies" "$steps" "$WORK/uneven.h5")
      awk -v p="$p" -v slabs="$slabs" '{
        for (i = 1; i <= NF; i++) { split($i, kv, "="); v[kv[1]] = kv[2] }
        printf "| %s | %s | %s | %s | %s | %s |\n", p, slabs, v["grains"], v["work_imbalance"], v["force_imbalance"],
          v["ms_per_step"] }' <<<"$line"
    done
  done
  rm -f "$WORK"/uneven.h5*
}

if [[ $MODE == restart ]]; then restart_table; else uneven_table; fi
