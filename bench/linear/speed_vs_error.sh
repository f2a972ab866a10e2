#!/usr/bin/env bash
# Speed against error of every forward model at one point (omega_hat = 0.5, gamma_hat = 0.1), from
# one run of bench_speed_vs_error on the shipped packings: three N = 2000 (linear_w3) and five
# N = 10^4 (field_w3) W = 3 channels; and on five N = 5*10^4 and five N = 2.5*10^5 channels stacked
# from periodic 2000-grain cells (seeds 1-5; docs/linear.md, "Channels of 10^5 to 10^6 grains"),
# prepared here first. The time-domain DEM runs on the first packing of the two smaller sizes for 10
# and 40 drive periods. The reference is the five N = 10^4 channels (directly prepared, unlike the
# stacked ones, whose disorder repeats every cell). Prints the table and draws error against wall
# time, log-log, into docs/images/speed_vs_error.{png,svg} (docs/performance.md). Several minutes
# on one core, 12 GB of memory.
#
#   bench/linear/speed_vs_error.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail
shopt -s inherit_errexit  # a failing preparation inside $(stack ...) stops the script
here=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$here/build}
out=${2:-$here/docs/images}
t=$here/data/tables
rows=$(mktemp --suffix=.tsv)
stacked=$(mktemp -d)
series=$(mktemp -d)  # one file per plotted series: columns seconds, err_alpha, err_c
trap 'rm -rf "$rows" "$series" "$stacked"' EXIT

# The field scene with its column stacked from periodic 2000-grain cells, five members.
stack() {  # grains -> packing files (member 0 first)
  "$here/bench/linear/stacked_field_scene.sh" "$1" > "$stacked/s$1.toml"
  "$build/bin/sedwave" forward "$stacked/s$1.toml" --out "$stacked/r$1.h5" --packing-out "$stacked/p$1.h5" >/dev/null
  echo "$stacked/p$1.h5" "$stacked"/p$1.member{1,2,3,4}.h5
}
big=$(stack 50000)
huge=$(stack 250000)

# shellcheck disable=SC2086  # $big, $huge: lists of files
"$build/bin/bench_speed_vs_error" --omega-hat 0.5 --gamma-hat 0.1 --dem 10 --dem 40 --dem-max-grains 10000 \
  --reference 10000 --rows "$rows" \
  "$t/linear_w3.packing.h5" "$t/linear_w3.packing.member1.h5" "$t/linear_w3.packing.member2.h5" \
  "$t/field_w3.packing.h5" "$t/field_w3.packing.member1.h5" "$t/field_w3.packing.member2.h5" \
  "$t/field_w3.packing.member3.h5" "$t/field_w3.packing.member4.h5" $big $huge

mkdir -p "$out"
awk -F'\t' -v dir="$series" '
  /^#/ { next }
  $1 ~ /^1D/                          { f = "theory" }
  $1 ~ /^3D linear/ { f = ($2 ~ /^2000 / ? "2000" : $2 ~ /^10000 / ? "10000" : "stacked") }
  $1 ~ /^3D linear \(one/            { f = "one_" f }
  $1 ~ /^3D linear \(ens/            { f = (f == "stacked" ? "ensemble_stacked" : "ensemble") }
  $1 ~ /^3D time-domain/              { f = "dem" }
  $1 ~ /^linear, layers/              { next }
  { print $3, $4, $5 > (dir "/" f) }' "$rows"

plot_one() {  # column of the error: 2 (alpha_hat) or 3 (c_hat)
  echo "plot '$series/theory' u 1:$1 w p pt 7 ps 1.5 t '1D continuum, lattice', \\"
  echo "     '$series/one_2000' u 1:$1 w p pt 5 t '3D linear, one N = 2000 packing', \\"
  echo "     '$series/one_10000' u 1:$1 w p pt 4 t '3D linear, one N = 10^4 packing', \\"
  echo "     '$series/one_stacked' u 1:$1 w p pt 6 t '3D linear, one stacked packing (5·10^4, 2.5·10^5)', \\"
  echo "     '$series/ensemble' u 1:$1 w p pt 9 ps 1.5 t '3D linear, ensemble (3 x 2000)', \\"
  echo "     '$series/ensemble_stacked' u 1:$1 w p pt 11 ps 1.5 t '3D linear, stacked ensembles (5 x 5·10^4, 5 x 2.5·10^5)', \\"
  echo "     '$series/dem' u 1:$1 w p pt 13 ps 1.5 t '3D DEM, one packing (2000, 10^4; 10, 40 periods)'"
}
plot_body=$(cat <<GNUPLOT
set logscale xy
set format x "10^{%T}"
set format y "10^{%T}"
set xlabel "wall time per point [s]"
set key below
set grid
set multiplot layout 2,1
set ylabel "|α̂/α̂_{ref} − 1|"
set title "ω̂ = 0.5, γ̂ = 0.1; reference: 3D linear ensemble of 5 x N = 10^4 (its own error 2 % in α̂, 1.5 % in ĉ)"
$(plot_one 2)
set ylabel "|ĉ/ĉ_{ref} − 1|"
unset title
$(plot_one 3)
unset multiplot
GNUPLOT
)
gnuplot <<GNUPLOT
set terminal pngcairo size 900,1000 enhanced font 'Sans,11'
set output '$out/speed_vs_error.png'
$plot_body
set terminal svg size 900,1000 enhanced font 'Sans,11'
set output '$out/speed_vs_error.svg'
$plot_body
GNUPLOT
echo "plot: $out/speed_vs_error.png and .svg"
