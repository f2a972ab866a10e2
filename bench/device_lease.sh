#!/usr/bin/env bash
# Every many-core measurement in one time-budgeted run, for a lent machine that has none of the
# project's packages: the pack of bench/dem/pack_for_device.sh (carried as .device/) holds the
# programs and libraries. Phases, most wanted first; none starts after DEADLINE_S seconds, each is
# bounded so that the whole run ends within about DEADLINE_S + 60 s:
#   0. the machine's cores: the force loop on one 15 625-grain cell (`dem_bench loop`) and the
#      STREAM triad (bench/dem/stream_triad.c), each on one core alone, then on 2 cores (two pairs),
#      half the cores and all of them at once: what a core delivers when its neighbours work too
#   1. 10^7 grains (640 stacked copies of the relaxed 15 625-grain cell, periodic): sedwave on 16
#      ranks and 1, LAMMPS on 16 (bench/dem/device_scaling.sh, series strong_1e7)
#   2. a 10^7-grain channel tiled on 16 ranks, run and checkpointed, then restarted on 5 ranks
#      (bench/dem/tiled_channel.sh restart)
#   3. uneven work on 16 and 8 ranks: fixed slabs against slabs balanced on pairs, twice
#      (bench/dem/tiled_channel.sh uneven; 64 copies, the upper half loose)
#   4. the comparison of all six models on 1 and 16 threads (bench/compare_threads.sh)
#   5. strong and weak scaling against LAMMPS with what time is left (bench/dem/device_scaling.sh)
#
# Usage (repository root; .device made here by bench/dem/pack_for_device.sh):
#   OUT=DIR DEADLINE_S=450 bash bench/device_lease.sh
# DIR receives lease.log (everything printed), one table file per phase and logs.tar.gz (every
# run's own logs), at most 8 files. PHASES (default "0 1 2 3 4 5") picks phases; SMALL=1 shrinks every
# size and step count, to check the script on a small machine.
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
OUT=${OUT:-$PWD/lease-out}
DEADLINE_S=${DEADLINE_S:-450}
PHASES=${PHASES:-0 1 2 3 4 5}
SMALL=${SMALL:-0}
mkdir -p "$OUT"
RESULTS=$(mktemp -d /tmp/sedwave-lease.XXXXXX)
TREE=${PACK_TREE:-/tmp/sedwave-dem-pack}
exec > >(tee -a "$OUT/lease.log") 2>&1

left() { echo $((DEADLINE_S - SECONDS)); }
say() { echo "[$(printf '%4d' "$SECONDS") s] $*"; }
# phase N BUDGET NAME COMMAND...: runs when N is wanted and time is left, killed after BUDGET s or
# the deadline + 60 s, whichever comes first; its table goes to OUT/phaseN.md.
phase() {
  local n=$1 budget=$2 name=$3
  shift 3
  [[ " $PHASES " == *" $n "* ]] || return 0
  local cap=$(($(left) + 60))
  ((cap > budget)) && cap=$budget
  if (($(left) <= 0)); then say "phase $n ($name) skipped: the deadline has passed"; return 0; fi
  say "phase $n: $name (at most $cap s)"
  # timeout signals the whole process group (mpirun and its ranks too); bash -c sees the exported
  # helper functions below.
  timeout "$cap" bash -c '"$@"' _ "$@" >"$OUT/phase$n.md" 2>"$RESULTS/phase$n.err"
  local code=$?
  cat "$OUT/phase$n.md"
  ((code == 0)) || { say "phase $n ended with exit $code"; tail -20 "$RESULTS/phase$n.err"; }
}

say "unpacking the pack"
PACK_TREE=$TREE UNPACK_ONLY=1 bash "$ROOT/.device/run.sh" || { say "cannot unpack .device/pack.tar.xz"; exit 1; }
# shellcheck source=/dev/null
source "$TREE/env.sh"
cat /proc/loadavg
grep -m1 'model name' /proc/cpuinfo
nproc

# Ranks bound to cores where hwloc sees 16 of them, else to hardware threads, else unbound.
BIND="--bind-to none"
for binding in "--bind-to core --map-by core" "--bind-to hwthread --map-by hwthread"; do
  # shellcheck disable=SC2086
  if pack_env mpirun -np 16 $binding true >/dev/null 2>&1; then BIND=$binding; break; fi
done
say "binding: $BIND"
LAUNCH="env LD_LIBRARY_PATH=$PACK_LIBS mpirun $BIND"
CELL=$TREE/packings/packing_15625.data
COPIES_BIG=640 STEPS_BIG=20 COPIES_UNEVEN=64 STEPS_UNEVEN=200 RANKS_BIG=16
if ((SMALL)); then COPIES_BIG=8 STEPS_BIG=4 COPIES_UNEVEN=4 STEPS_UNEVEN=40 RANKS_BIG=2; fi

scaling() {  # OUT-subfolder, then environment settings for device_scaling.sh
  local dir=$RESULTS/$1
  shift
  env OUT="$dir" "$@" bash "$TREE/bench/device_scaling.sh" "$TREE" >/dev/null 2>"$dir.err"
  cat "$dir/table.md"
}
channel() {  # mode, then environment settings for tiled_channel.sh
  local mode=$1
  shift
  env BENCH="$TREE/usr/bin/dem_bench" CELL="$CELL" MPIRUN="$LAUNCH" WORK="$RESULTS/channel" "$@" \
    bash "$TREE/bench/tiled_channel.sh" "$mode"
}
# The force loop's median ns per grain and the triad's median GB/s, one line per placement of
# processes on cores ("cpus 0,8": one process on each), each process timed while the others run.
cores() {
  local n np set loop triad
  # shellcheck source=/dev/null
  source "$TREE/env.sh"
  n=$(nproc)
  lscpu | grep -E '^(Model name|Thread\(s\)|Core\(s\)|Socket\(s\)|NUMA node|L2|L3|CPU max MHz)' | sed 's/^/    /'
  echo "| processes | cpus | force loop ns/grain per process (min / median / max) | triad GB/s per process (min / median / max) | triad GB/s, sum |"
  echo "|---|---|---|---|---|"
  for set in "0" "0,1" "0,$((n / 2))" "0-$((n / 2 - 1))" "0-$((n - 1))"; do
    np=$(awk -F, '{k = 0; for (i = 1; i <= NF; ++i) {split($i, r, "-"); k += (r[2] == "" ? 1 : r[2] - r[1] + 1)} print k}' <<<"$set")
    # shellcheck disable=SC2086
    loop=$(pack_env mpirun -np "$np" --cpu-set "$set" $BIND dem_bench loop "$CELL" 2>/dev/null |
           awk '$1 == "dry" {print $2}')
    # shellcheck disable=SC2086
    triad=$(pack_env mpirun -np "$np" --cpu-set "$set" $BIND stream_triad 2>/dev/null |
            sed -nE 's/.*triad_gb_s_median=([0-9.]+).*/\1/p')
    printf '| %s | %s | %s | %s | %s |\n' "$np" "$set" "$(summary "$np" <<<"$loop")" "$(summary "$np" <<<"$triad")" \
      "$(awk '{s += $1} END {printf "%.1f", s}' <<<"$triad")"
  done
}
# shellcheck source=dem/summary.sh
source "$ROOT/bench/dem/summary.sh"
export -f scaling channel cores summary
export RESULTS TREE CELL LAUNCH BIND
sedwave_wrapper=$RESULTS/sedwave
printf '#!/bin/sh\nexec env LD_LIBRARY_PATH="%s" "%s" "$@"\n' "$PACK_LIBS" "$TREE/usr/bin/sedwave" >"$sedwave_wrapper"
chmod +x "$sedwave_wrapper"
mkdir -p "$RESULTS/channel"

phase 0 90 "the cores: force loop and memory bandwidth, alone and with every core busy" cores
if ((SMALL)); then
  phase 1 200 "10^7 grains, sedwave against LAMMPS (small check)" scaling huge SERIES=strong_1e7 PASSES=1 \
    BUDGET_S=60 COPIES_1E7=16 STEPS_DIVISOR=10 RANKS_1E7="2 1" LAMMPS_RANKS_1E7=2
else
  phase 1 240 "10^7 grains, sedwave on 16 and 1 ranks, LAMMPS on 16" scaling huge SERIES=strong_1e7 PASSES=1 \
    BUDGET_S=150
fi
phase 2 150 "10^7-grain channel: tile, run, checkpoint on 16 ranks; restart on 5" channel restart \
  COPIES=$COPIES_BIG STEPS=$STEPS_BIG WRITE_RANKS=$RANKS_BIG RESTART_RANKS=5
phase 3 90 "uneven work: fixed slabs against slabs balanced on pairs" bash -c \
  'for pass in 1 2; do "$@" || exit; done' _ channel uneven COPIES=$COPIES_UNEVEN STEPS=$STEPS_UNEVEN \
  RANKS="$RANKS_BIG $((RANKS_BIG / 2))"
models=lattice,saturated-lattice,biot-stoll,edfm,grain-shearing,vgs-lambda
((SMALL)) && models=lattice,edfm
phase 4 200 "sedwave compare, six models, 1 against 16 threads" env CPUS="0-$(($(nproc) - 1))" \
  THREADS="1 $(nproc)" MODELS=$models bash "$ROOT/bench/compare_threads.sh" 1 "$sedwave_wrapper"
if ((SMALL)); then
  phase 5 120 "strong and weak scaling (small check)" scaling scaling BUDGET_S=30 PASSES=1 RANKS="1 2" \
    STEPS_DIVISOR=20
else
  phase 5 400 "strong and weak scaling against LAMMPS" scaling scaling BUDGET_S=$(($(left) - 30)) PASSES=2
fi

say "done; packing the logs"
tar -C "$RESULTS" -czf "$OUT/logs.tar.gz" --exclude='channel' --exclude='*.data' --exclude='sedwave' . 2>/dev/null
rm -rf "$RESULTS"
