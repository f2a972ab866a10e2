#!/usr/bin/env bash
# One broadband pulse against one sinusoidal run per frequency, on the same shipped packing
# (data/tables/thesis_w3_small.packing.h5, 1000 grains, W = 3) and the same dashpot: a linear
# response has one transfer function, so both must give the same alpha_hat and c_hat, and the
# pulse gets all frequencies for the price of about one sinusoid.
#
# Usage: bench/channel/pulse_vs_sinusoid.sh [build-dir] [gamma_hat...]   (default: build, 1 0.1)
#        SIGNAL=chirp drives a logarithmic chirp over the same band instead of the Gaussian pulse.
#        FIT_DEPTH=D fits only layers within D mean diameters of the driven wall, in both runs (a
#        broadband run with more signal keeps deeper layers than the sinusoid; in one disordered
#        packing the fitted decay depends on the stretch fitted, so compare like with like).
# Prints a markdown table per gamma_hat: omega_hat, pulse and sinusoid alpha_hat and c_hat with
# standard errors, their distance in combined sigmas, and the wall time of each run.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-$ROOT/build}
shift || true
GAMMAS=${*:-"1 0.1"}
SEDWAVE=$BUILD/bin/sedwave
PACKING=$ROOT/data/tables/thesis_w3_small.packing.h5
SCENE=$ROOT/data/scenes/table_small_scene.toml
WORK=$(mktemp -d /tmp/sedwave-pulse.XXXXXX)
trap 'rm -rf "$WORK"' EXIT

SIGNAL=${SIGNAL:-pulse}
cp "$SCENE" "$WORK/sinusoid.toml"
if [[ -n "${FIT_DEPTH:-}" ]]; then printf '\n[drive.measurement]\nmax_fit_depth = %s\n' "$FIT_DEPTH" >> "$WORK/sinusoid.toml"; fi
SCENE=$WORK/sinusoid.toml
# The table scene with the sinusoid replaced by a pulse (or chirp) over omega_hat 0.2 .. 1.8.
sed -e "s/^omega_hat = .*/signal = \"$SIGNAL\"\nomega_hat_min = 0.2\nomega_hat_max = 1.8\nfrequencies = 9/" "$SCENE" > "$WORK/pulse.toml"

seconds() { local t0 t1; t0=$(date +%s.%N); "$@" > "$WORK/out.txt" || true; t1=$(date +%s.%N); awk -v a="$t0" -v b="$t1" "BEGIN { printf \"%.1f\", b - a }"; }

for g in $GAMMAS; do
  tp=$(seconds "$SEDWAVE" forward "$WORK/pulse.toml" --packing "$PACKING" --gamma-hat "$g" --out "$WORK/pulse.h5")
  cp "$WORK/out.txt" "$WORK/pulse.txt"
  echo
  echo "gamma_hat = $g; the $SIGNAL run took $tp s for all frequencies"
  echo
  echo "| omega_hat | pulse alpha_hat | sinusoid alpha_hat | apart | pulse c_hat | sinusoid c_hat | apart | sinusoid run [s] |"
  echo "|---:|---|---|---:|---|---|---:|---:|"
  grep -E '^  omega_hat' "$WORK/pulse.txt" | while read -r _ w rest; do
    ts=$(seconds "$SEDWAVE" forward "$SCENE" --packing "$PACKING" --omega-hat "$w" --gamma-hat "$g" --out "$WORK/s.h5")
    s=$(grep -E '^alpha_hat|^not measured' "$WORK/out.txt" | head -1)
    awk -v w="$w" -v p="$rest" -v s="$s" -v ts="$ts" 'BEGIN {
      np = split(p, a, " "); ns = split(s, b, " ");
      pm = (a[1] == "alpha_hat"); sm = (b[1] == "alpha_hat");
      pa = pm ? sprintf("%.4f ± %.4f", a[2], a[4]) : "not measured";
      pc = pm ? sprintf("%.4f ± %.4f", a[6], a[8]) : "";
      sa = sm ? sprintf("%.4f ± %.4f", b[2], b[4]) : "not measured";
      sc = sm ? sprintf("%.4f ± %.4f", b[6], b[8]) : "";
      da = (pm && sm) ? sprintf("%.1f σ", (a[2] - b[2]) / sqrt(a[4]^2 + b[4]^2)) : "";
      dc = (pm && sm) ? sprintf("%.1f σ", (a[6] - b[6]) / sqrt(a[8]^2 + b[8]^2)) : "";
      printf "| %s | %s | %s | %s | %s | %s | %s | %.1f |\n", w, pa, sa, da, pc, sc, dc, ts }'
  done
done
