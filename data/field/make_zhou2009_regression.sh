#!/bin/sh
# Regenerates zhou2009_regression.csv (next to this script) from the regressions of
#   Ji-Xun Zhou, Xue-Zhen Zhang, D. P. Knobles (2009), "Low-frequency geoacoustic model for the
#   effective properties of sandy seabottoms", J. Acoust. Soc. Am. 125(5), 2847-2866,
#   doi:10.1121/1.3089218.
# The rows are points SAMPLED FROM THE PUBLISHED REGRESSIONS, NOT measurements (see README.md).
#
# Usage: sh data/field/make_zhou2009_regression.sh [OUTPUT]   (default: the shipped CSV)
# POSIX sh + awk only. Every number goes through an explicit printf format (never awk's
# OFMT/CONVFMT) under LC_ALL=C, so a rerun reproduces the shipped file byte for byte.
set -eu

here=$(cd "$(dirname "$0")" && pwd)
out=${1:-"$here/zhou2009_regression.csv"}

LC_ALL=C awk '
# Print x with 6 significant digits and return the printed value, so that later columns are
# computed from exactly what the file says.
function sig6(x) { return sprintf("%.6g", x) + 0 }

BEGIN {
  print "# sedwave observation CSV (format: docs/file-formats.md)"
  print "# WARNING: NOT MEASUREMENTS. Every row is a point SAMPLED FROM A PUBLISHED REGRESSION"
  print "# WARNING: (Zhou, Zhang & Knobles 2009). Rows are correlated through the regression parameters."
  print "# data_kind: points sampled from a published regression; NOT measurements"
  print "# citation: Ji-Xun Zhou, Xue-Zhen Zhang, D. P. Knobles (2009), \"Low-frequency geoacoustic model for the effective properties of sandy seabottoms\", J. Acoust. Soc. Am. 125(5), 2847–2866"
  print "# doi: 10.1121/1.3089218"
  print "# sites: 20 shallow-water sandy sites (the regressions summarise inversion results from all of them)"
  print "# attenuation_regression: alpha[dB/m] = (0.37 +/- 0.01) * (f / 1000 Hz)^(1.80 +/- 0.02), valid 50-1000 Hz; +/- taken as 1 sigma of the fit parameters"
  print "# attenuation_sampling: 13 log-spaced frequencies 50..1000 Hz inclusive (6 significant digits); value = regression at the printed frequency (6 significant digits)"
  print "# attenuation_sigma: value * sqrt((0.01/0.37)^2 + (0.02*ln(f/1000 Hz))^2), the 1 sigma of the regression parameters propagated to alpha, NEGLECTING their correlation; not a measurement error"
  print "# sound_speed_ratio_regression: c_sediment / c_bottom_water = 1.061 +/- 0.009, valid 50-600 Hz; sampled at 6 log-spaced frequencies 50..600 Hz"
  print "# water_sound_speed_m_per_s: 1500"
  print "# water_sound_speed_note: NOMINAL ASSUMPTION, not from the paper (the paper gives ratios to the bottom-water sound speed of each site)"
  print "# units: frequency in Hz; attenuation value and sigma in dB/m; sound_speed_ratio value and sigma dimensionless (ratio)"
  print "# generated_by: data/field/make_zhou2009_regression.sh"
  print "quantity,frequency,frequency_unit,value,value_unit,sigma"

  # Attenuation: 13 points, f = 50 * 20^(i/12) Hz.
  for (i = 0; i <= 12; i++) {
    f = sig6(50 * exp(log(20) * i / 12))
    x = log(f / 1000)
    alpha = sig6(0.37 * exp(1.80 * x))
    sigma = sig6(alpha * sqrt((0.01 / 0.37)^2 + (0.02 * x)^2))
    printf "attenuation,%.6g,Hz,%.6g,dB/m,%.6g\n", f, alpha, sigma
  }
  # Sound-speed ratio: 6 points, f = 50 * 12^(i/5) Hz.
  for (i = 0; i <= 5; i++) {
    f = sig6(50 * exp(log(12) * i / 5))
    printf "sound_speed_ratio,%.6g,Hz,1.061,ratio,0.009\n", f
  }
}' > "$out"
