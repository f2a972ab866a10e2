#!/usr/bin/env bash
# Strong and weak scaling of the DEM engine against LAMMPS on one many-core node, both codes on the
# same packings and steps, alternating run by run; time-budgeted for a lent machine.
#
# Scene: the thesis scene of run_vs_lammps.sh (frictionless Hooke, W = 3 channel periodic along all
# axes, Newton's third law on in both codes). Packings: 5e4 grains (prepared), and 15 625 grains
# (prepared) stacked 1, 2, 4, 8 and 16 times along z; 16 copies are the 2.5e5-grain packing.
#   strong scaling  5e4 and 2.5e5 grains on 1, 2, 4, 8, 16 ranks
#   weak scaling    15 625 grains per rank, 1 -> 16 ranks
#   strong_1e7      (only when named in SERIES) 640 stacked copies, 10^7 grains: sedwave on
#                   RANKS_1E7 (default "16 1"), LAMMPS on LAMMPS_RANKS_1E7 (default "16"), 20 steps;
#                   the stacked file is about 1.7 GB (COPIES_1E7 copies instead of 640, to check)
# Each (packing, ranks) runs every packed sedwave build, then LAMMPS; the next pass runs them in the
# reverse order, until the budget is spent. 10^7 grains on one rank (about a minute per run) runs
# the first build alone (dem_bench, or the first variant under ONLY_VARIANTS).
#
# Usage: bench/dem/device_scaling.sh [pack-dir]
#   pack-dir   made by bench/dem/pack_for_device.sh (default: this script's folder if it holds
#              env.sh, else .device at the repository root)
#   OUT        where raw numbers, logs and the table go (default ./scaling-out)
#   BUDGET_S   no run starts after this many seconds (default 420); PASSES (default 2); RANKS;
#   STEPS_DIVISOR  divides every run's steps (a quick check of the script: 20)
#   SERIES     which series run (default "strong_5e4 weak strong_2.5e5"); LAMMPS=0 leaves LAMMPS out;
#              VARIANTS, ONLY_VARIANTS: dem_bench with an environment setting (see below)
#              (e.g. to compare packed sedwave builds alone: SERIES=strong_5e4 RANKS="2 4" LAMMPS=0)
# Prints the table at the end (also $OUT/table.md); $OUT/raw.txt holds one key=value line per run.
set -uo pipefail
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
if [[ -f $HERE/env.sh ]]; then DEFAULT_PACK=$HERE; else DEFAULT_PACK=$(cd "$HERE/../.." && pwd)/.device; fi
PACK=$(cd "${1:-$DEFAULT_PACK}" && pwd)
OUT=${OUT:-$PWD/scaling-out}
BUDGET_S=${BUDGET_S:-420}
PASSES=${PASSES:-2}
RANKS=${RANKS:-"1 2 4 8 16"}
DIVISOR=${STEPS_DIVISOR:-1}
SERIES=${SERIES:-"strong_5e4 weak strong_2.5e5"}
WITH_LAMMPS=${LAMMPS:-1}
mkdir -p "$OUT/logs"
# shellcheck source=/dev/null
source "$PACK/env.sh"
BENCH_FILES=$PACK/bench
[[ -f $BENCH_FILES/in.thesis.lmp ]] || BENCH_FILES=$HERE
WORK=$(mktemp -d /tmp/dem-scaling.XXXXXX)
RAW=$OUT/raw.txt
: >"$RAW"

log() { echo "[$(printf '%4d' "$SECONDS") s] $*" | tee -a "$OUT/progress.txt"; }
left() { echo $((BUDGET_S - SECONDS)); }
# A run that starts before the budget ends gets at most 60 s beyond it.
bounded() { local t=$(( $(left) + 60 )); if command -v timeout >/dev/null; then timeout "$t" "$@"; else "$@"; fi; }

{
  echo "date: $(date -u 2>/dev/null)"
  echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2-)"
  echo "logical cpus: $(nproc 2>/dev/null || grep -c ^processor /proc/cpuinfo)"
  echo "memory: $(grep MemTotal /proc/meminfo)"
  echo "kernel: $(uname -r)"
  echo "load: $(cat /proc/loadavg)"
} >"$OUT/machine.txt"
cat "$OUT/machine.txt"

# Bind each rank to a core where hwloc sees enough cores for the largest run; else to a hardware
# thread; else unbound.
max_ranks=$(tr ' ' '\n' <<<"$RANKS" | sort -n | tail -1)
BIND=()
for binding in "--bind-to core --map-by core" "--bind-to hwthread --map-by hwthread" "--bind-to none"; do
  read -r -a try <<<"$binding"
  if pack_env mpirun -np "$max_ranks" "${try[@]}" dem_bench params >"$OUT/logs/bind_check.txt" 2>&1; then
    BIND=("${try[@]}"); break
  fi
  log "mpirun -np $max_ranks $binding failed (logs/bind_check.txt)"
done
(( ${#BIND[@]} )) || { log "mpirun failed:"; cat "$OUT/logs/bind_check.txt"; exit 1; }
log "binding: ${BIND[*]}"
echo "binding: ${BIND[*]}" >>"$OUT/machine.txt"
read -r KN GAMMA_N DT <"$PACK/packings/params.txt"

# ---- packings -----------------------------------------------------------------------------------
declare -A DATA=() STEPS=() GRAINS=()
DATA[strong_5e4]=$PACK/packings/packing_50000.data; STEPS[strong_5e4]=$((400 / DIVISOR)); GRAINS[strong_5e4]=50000
stacks="1 2 4 8 16"
[[ " $SERIES " == *" weak "* ]] || stacks=16
[[ " $SERIES " == *" weak "* || " $SERIES " == *" strong_2.5e5 "* ]] || stacks=
for p in $stacks; do
  DATA[weak_$p]=$WORK/weak_$p.data
  if [[ $p == 1 ]]; then cp "$PACK/packings/packing_15625.data" "${DATA[weak_1]}"
  else pack_env mpirun -np 1 dem_bench stack "$PACK/packings/packing_15625.data" "$p" "${DATA[weak_$p]}" >/dev/null; fi
  STEPS[weak_$p]=$((300 / DIVISOR)); GRAINS[weak_$p]=$((15625 * p))
done
STEPS[weak_16]=$((200 / DIVISOR)) GRAINS[weak_16]=250000  # also the 2.5e5-grain strong-scaling packing
if [[ " $SERIES " == *" strong_1e7 "* ]]; then
  copies=${COPIES_1E7:-640}  # fewer to check the script on a small machine
  DATA[strong_1e7]=$WORK/strong_1e7.data; STEPS[strong_1e7]=$((20 / DIVISOR < 2 ? 2 : 20 / DIVISOR)); GRAINS[strong_1e7]=$((15625 * copies))
  pack_env mpirun -np 1 dem_bench stack "$PACK/packings/packing_15625.data" "$copies" "${DATA[strong_1e7]}" >/dev/null
fi
log "packings ready in $WORK"

# (packing, ranks) configurations: strong 5e4, weak 1..8, strong 2.5e5 (= weak 16)
CONFIGS=()
for series in $SERIES; do
  case $series in
    strong_5e4) for p in $RANKS; do CONFIGS+=("strong_5e4:$p"); done ;;
    weak) for p in 1 2 4 8; do [[ " $RANKS " == *" $p "* ]] && CONFIGS+=("weak_$p:$p"); done ;;
    strong_2.5e5) for p in $RANKS; do CONFIGS+=("weak_16:$p"); done ;;
    strong_1e7) for p in ${RANKS_1E7:-16 1}; do CONFIGS+=("strong_1e7:$p"); done ;;
    *) echo "device_scaling: unknown series $series" >&2; exit 2 ;;
  esac
done
BUILDS=()
for b in "$PACK"/usr/bin/dem_bench*; do BUILDS+=("$(basename "$b")"); done
# VARIANTS="name:VAR=VALUE ..." adds dem_bench runs with an environment setting, recorded as build
# dem_bench@name (e.g. balanced:DEM_BENCH_BALANCE_EVERY=20); ONLY_VARIANTS=1 runs those alone.
declare -A VARIANT_ENV=()
[[ ${ONLY_VARIANTS:-0} == 1 ]] && BUILDS=()
for v in ${VARIANTS:-}; do BUILDS+=("dem_bench@${v%%:*}"); VARIANT_ENV[dem_bench@${v%%:*}]=${v#*:}; done

run_sedwave() {  # build packing ranks pass
  local build=$1 packing=$2 ranks=$3 pass=$4 line
  local setting=${VARIANT_ENV[$build]:-DEM_BENCH_NEWTON=on}
  line=$(DEM_BENCH_NEWTON=on bounded env LD_LIBRARY_PATH="$PACK_LIBS" "$setting" mpirun -np "$ranks" "${BIND[@]}" \
         -x "${setting%%=*}" "${build%@*}" run "${DATA[$packing]}" "${STEPS[$packing]}" \
         2>"$OUT/logs/${build}_${packing}_${ranks}_$pass.err")
  if [[ $line == ns_per_grain_step=* ]]; then
    echo "code=sedwave build=$build packing=$packing pass=$pass $line" >>"$RAW"
    log "$build $packing ranks=$ranks: $(sed -E 's/.*ms_per_step=([0-9.]+).*/\1/' <<<"$line") ms/step"
  else
    log "$build $packing ranks=$ranks FAILED (logs/${build}_${packing}_${ranks}_$pass.err)"
  fi
}

run_lammps() {  # packing ranks pass
  local packing=$1 ranks=$2 pass=$3 steps=${STEPS[$1]} n=${GRAINS[$1]}
  local tag=lammps_${packing}_${ranks}_$pass
  local rss=$WORK/rss_$tag
  mkdir -p "$rss"
  PEAK_RSS_DIR=$rss bounded env LD_LIBRARY_PATH="$PACK_LIBS" mpirun -np "$ranks" "${BIND[@]}" -x PEAK_RSS_DIR \
    peak_rss lmp -in "$BENCH_FILES/in.thesis.lmp" -log none -screen "$OUT/logs/$tag.log" \
    -var data "${DATA[$packing]}" -var kn "$KN" -var gamma_n "$GAMMA_N" -var dt "$DT" -var newton on \
    -var warm $((steps / 10)) -var steps "$steps" >/dev/null 2>"$OUT/logs/$tag.err"
  local line
  line=$(awk -v n="$n" -v ranks="$ranks" '
    /^Loop time/ {t = $4; s = $9}
    /^Per MPI rank memory allocation/ {mem = $(NF-5) "/" $(NF-3) "/" $(NF-1)}
    /^(Pair|Neigh|Comm|Modify|Output|Other) +\|/ {split($0, c, "|"); avg[$1] = c[3] + 0; max[$1] = c[4] + 0}
    END {
      if (s == 0) exit 1
      printf "ns_per_grain_step=%.2f ranks=%d grains=%d steps=%d ms_per_step=%.4f", 1e9 * t / (n * s), ranks, n, s, 1e3 * t / s
      printf " force_ms=%.4f/%.4f neighbour_ms=%.4f/%.4f communication_ms=%.4f/%.4f integration_ms=%.4f/%.4f", \
        1e3 * avg["Pair"] / s, 1e3 * max["Pair"] / s, 1e3 * avg["Neigh"] / s, 1e3 * max["Neigh"] / s, \
        1e3 * avg["Comm"] / s, 1e3 * max["Comm"] / s, 1e3 * avg["Modify"] / s, 1e3 * max["Modify"] / s
      printf " lammps_mem_mb_min_avg_max=%s", mem
    }' "$OUT/logs/$tag.log") || { log "LAMMPS $packing ranks=$ranks FAILED (logs/$tag.*)"; return; }
  local mb
  mb=$(cat "$rss"/rank_*.txt 2>/dev/null | sort -n | awk '{v[NR] = $1 / 1024} END {if (NR) printf "peak_rss_mb_min=%.1f peak_rss_mb_median=%.1f peak_rss_mb_max=%.1f", v[1], v[int(NR / 2) + 1], v[NR]}')
  echo "code=lammps build=lmp packing=$packing pass=$pass $line $mb" >>"$RAW"
  log "lammps $packing ranks=$ranks: $(sed -E 's/.*ms_per_step=([0-9.]+).*/\1/' <<<"$line") ms/step"
}

# LAMMPS on every configuration but the 10^7-grain one off LAMMPS_RANKS_1E7 (one LAMMPS rank
# needs about 5 s per step there).
lammps_wanted() {  # packing ranks
  (( WITH_LAMMPS )) || return 1
  [[ $1 != strong_1e7 || " ${LAMMPS_RANKS_1E7:-16} " == *" $2 "* ]]
}

for ((pass = 1; pass <= PASSES; ++pass)); do
  order=("${CONFIGS[@]}")
  for config in "${order[@]}"; do
    packing=${config%%:*} ranks=${config##*:}
    (( $(left) > 0 )) || { log "budget spent: pass $pass stops before $packing ranks=$ranks"; break 2; }
    builds=("${BUILDS[@]}")
    [[ $packing == strong_1e7 && $ranks == 1 && ${#builds[@]} -gt 1 ]] && builds=("${BUILDS[0]}")
    if (( pass % 2 == 1 )); then
      for b in "${builds[@]}"; do run_sedwave "$b" "$packing" "$ranks" "$pass"; done
      lammps_wanted "$packing" "$ranks" && run_lammps "$packing" "$ranks" "$pass"
    else
      lammps_wanted "$packing" "$ranks" && run_lammps "$packing" "$ranks" "$pass"
      for ((k = ${#builds[@]} - 1; k >= 0; --k)); do run_sedwave "${builds[k]}" "$packing" "$ranks" "$pass"; done
    fi
  done
done
rm -rf "$WORK"

python3 "$BENCH_FILES/scaling_table.py" "$RAW" >"$OUT/table.md" && cat "$OUT/table.md" ||
  log "no table (python3 failed); the raw numbers are in $RAW"
log "done"
