#!/usr/bin/env bash
# What the parallel code loses, apart from what the machine loses when all its cores work.
# Strong scaling compares P ranks with one rank running alone; on a node whose cores slow each other
# down (shared caches, memory bandwidth, clock limits, a virtual machine's neighbours) that ratio
# mixes the two. Here, per packing, side by side and alternating over PASSES:
#   alone   one rank (a singleton dem_bench run) on core 0, the other cores idle
#   loaded  the same run on every core at once (independent singletons, one per core)
#   P ranks one run of the packing on P = all cores (mpirun, ranks bound to cores)
# and the efficiencies t_alone / (P t_P) (strong scaling as usually quoted) and t_loaded / (P t_P)
# (against a core as fast as it is when all cores work: the parallel code's own loss).
#
# Usage: bench/dem/loaded_baseline.sh PACK FILE:STEPS...   (PACK: the unpacked tree of
#   pack_for_device.sh, with env.sh; PASSES default 2; BIND, mpirun's binding options, default
#   "--bind-to core --map-by core"). Prints a markdown table.
set -uo pipefail
PACK=$1
shift
# shellcheck source=/dev/null
source "$PACK/env.sh"
PASSES=${PASSES:-2}
BIND=${BIND:---bind-to core --map-by core}  # mpirun's binding of the P-rank run
P=$(nproc)
ms_per_step() { sed -nE 's/.*ms_per_step=([0-9.]+).*/\1/p'; }
# shellcheck source=summary.sh
source "$(dirname "${BASH_SOURCE[0]}")/summary.sh"
echo "| packing | steps | pass | alone ms/step | loaded ms/step, $P at once (min / median / max) | $P ranks ms/step | t_alone / ($P t_$P) | t_loaded / ($P t_$P) |"
echo "|---|---|---|---|---|---|---|---|"
for spec in "$@"; do
  file=${spec%:*} steps=${spec##*:}
  for ((pass = 1; pass <= PASSES; ++pass)); do
    alone=$(DEM_BENCH_NEWTON=on pack_env taskset -c 0 dem_bench run "$file" "$steps" 2>/dev/null | ms_per_step)
    loaded=$(for ((c = 0; c < P; ++c)); do
               DEM_BENCH_NEWTON=on pack_env taskset -c "$c" dem_bench run "$file" "$steps" 2>/dev/null | ms_per_step &
             done; wait)
    # shellcheck disable=SC2086
    ranks=$(DEM_BENCH_NEWTON=on pack_env mpirun -np "$P" $BIND -x DEM_BENCH_NEWTON \
              dem_bench run "$file" "$steps" 2>/dev/null | ms_per_step)
    loaded_median=$(median <<<"$loaded")
    awk -v f="$(basename "$file")" -v s="$steps" -v pass="$pass" -v a="$alone" -v l="$loaded_median" \
        -v spread="$(summary "$P" <<<"$loaded")" -v r="$ranks" -v p="$P" 'BEGIN {
      if (a == "" || l == "" || r == "") { printf "| %s | %s | %s | %s | %s | %s | failed | failed |\n", f, s, pass, a, spread, r; exit }
      printf "| %s | %s | %s | %.4g | %s | %.4g | %.0f %% | %.0f %% |\n", f, s, pass, a, spread, r, 100 * a / (p * r), 100 * l / (p * r) }'
  done
done
