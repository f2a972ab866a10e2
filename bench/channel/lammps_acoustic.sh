#!/usr/bin/env bash
# sedwave's driven channel against LAMMPS (Debian package `lammps`) on the same compressed packing
# and drive: per frequency, sedwave drives the packing and writes the LAMMPS input for the same run
# (pair granular Hooke with a constant normal dashpot, fix move wiggle on the lower wall, the same
# time step, length and sampling); LAMMPS runs it and dumps the flow grains' z; sedwave measures
# that dump with the same layers, windows, lock-ins and fit. Prints both results and their difference.
#
# usage: bench/channel/lammps_acoustic.sh [BUILD_DIR] [PACKING.h5]
#   (default packing: the shipped data/tables/thesis_w3_small.packing.h5, 1000 grains;
#    OMEGAS="0.3 0.6 1.0" GAMMA=0.1 to choose the points; about 1 min per point on one core)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-$ROOT/build}
PACKING=${2:-$ROOT/data/tables/thesis_w3_small.packing.h5}
OMEGAS=${OMEGAS:-"0.3 0.6 1.0"}
GAMMA=${GAMMA:-0.1}
WORK=${WORK:-$(mktemp -d /tmp/sedwave-lammps-acoustic.XXXXXX)}
command -v lmp >/dev/null || apt-get install -y lammps >/dev/null
cmake --build "$BUILD" --target bench_lammps_acoustic >/dev/null
echo "packing $PACKING, gamma_hat $GAMMA, frozen far end; LAMMPS: $(lmp -h | sed -n 's/^Large-scale.*- \(.*\) -.*/\1/p;2q' | head -1)"
echo
echo "| ω̂ | sedwave α̂ | LAMMPS α̂ | sedwave ĉ | LAMMPS ĉ | |Δα̂| / σ | |Δĉ| / σ | max |Δu| / A | layers | LAMMPS run [s] |"
echo "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for W in $OMEGAS; do
  dir="$WORK/w$W"
  mkdir -p "$dir"
  ours=$("$BUILD/bin/bench_lammps_acoustic" script "$PACKING" --omega-hat "$W" --gamma-hat "$GAMMA" --dir "$dir")
  start=$(date +%s%N)
  (cd "$dir" && lmp -in in.acoustic -log lmp.log -screen none)
  seconds=$(awk -v ns=$(( $(date +%s%N) - start )) 'BEGIN { printf "%.1f", ns / 1e9 }')
  theirs=$("$BUILD/bin/bench_lammps_acoustic" measure "$PACKING" --omega-hat "$W" --gamma-hat "$GAMMA" --dir "$dir")
  rm -f "$dir/dump.z" "$dir/sedwave_layers.txt"
  # fields: 1 engine, 7 alpha, 9 sigma_alpha, 11 c, 13 sigma_c, 15 layers, 16... problem
  echo "$ours"$'\n'"$theirs" | awk -v w="$W" -v s="$seconds" '
    NR == 1 { a1 = $7; sa = $9; c1 = $11; sc = $13; n = $15; p1 = ""; for (i = 16; i <= NF; ++i) p1 = p1 " " $i }
    NR == 2 { a2 = $7; c2 = $11; p2 = ""; for (i = 16; i <= NF; ++i) p2 = p2 " " $i }
    NR == 3 { du = $NF }
    END {
      if (p1 != "" || p2 != "") { printf "| %s | not measured:%s | %s | | | | | | %.1f |\n", w, p1, p2, s; exit }
      da = a1 - a2; if (da < 0) da = -da; dc = c1 - c2; if (dc < 0) dc = -dc
      printf "| %s | %.6f ± %.4f | %.6f | %.6f ± %.4f | %.6f | %.1e | %.1e | %s | %d | %.1f |\n", w, a1, sa, a2, c1, sc, c2, da / sa, dc / sc, du, n, s }'
done
