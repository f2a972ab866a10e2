#!/usr/bin/env bash
# Example 03: one driven channel with the discrete-element engine.
#
# `sedwave forward` drives one wall of a granular channel (W = 3 grains across, 1000 flow grains,
# Hooke contacts, compressed to P = 10) at one frequency, records each layer's motion and fits the
# attenuation alpha_hat and phase speed c_hat (dimensionless: docs/physics.md). The packing is the
# shipped one of the small table, so the run reproduces that table's point at the same
# (omega_hat, gamma_hat): one channel run is one table point.
#
#   examples/03-driven-channel/run.sh [SEDWAVE [OUT]]
source "$(dirname "$0")/../common.sh"

SCENE=$DATA/scenes/table_small_scene.toml          # the scene: geometry, contact law, drive
PACKING=$DATA/tables/thesis_w3_small.packing.h5     # its prepared packing (saves the preparation)
W=0.8 G=0.3                                         # omega_hat and gamma_hat of this run

step "The scene (every key: docs/scenes.md)"
grep -v '^\s*#' "$SCENE" | grep -v '^\s*$'

step "Drive the channel at omega_hat = $W, gamma_hat = $G"
# --packing reuses the prepared packing; without it the scene's [preparation] builds one
# (compression and relaxation: about a minute for this size) and --packing-out saves it.
# --omega-hat and --gamma-hat override the scene's drive. The run prints the front speed, the
# lock-in windows it chose, and the fit over the layers; run.h5 holds every layer's record.
run 0 "$SEDWAVE" forward "$SCENE" --packing "$PACKING" --omega-hat $W --gamma-hat $G --out run.h5 | tee forward.log

alpha=$(sed -n 's/^alpha_hat \([^ ]*\) +- \([^ ]*\) .*/\1/p' forward.log)
sigma=$(sed -n 's/^alpha_hat \([^ ]*\) +- \([^ ]*\) .*/\2/p' forward.log)
c=$(sed -n 's/.*c_hat \([^ ]*\) +- .*/\1/p' forward.log)
result alpha_hat "$alpha"
result c_hat "$c"

step "The same point in the shipped table (sedwave show prints a table as CSV)"
"$SEDWAVE" show "$DATA/tables/thesis_w3_small.h5" | awk -F, -v w=$W -v g=$G \
    'NR == 1 || /^omega_hat/ || ($1 + 0 == w && $2 + 0 == g)' | tee table_point.csv
table_alpha=$(awk -F, -v w=$W -v g=$G '$1 + 0 == w && $2 + 0 == g { print $4 }' table_point.csv)
table_c=$(awk -F, -v w=$W -v g=$G '$1 + 0 == w && $2 + 0 == g { print $6 }' table_point.csv)
# Same packing, same scene, same drive: the run must reproduce the table's values far inside the
# measurement's own error (a tenth of sigma). A change in the engine, the drive or the fit shows.
check "alpha_hat equals the table's within sigma/10" "abs($alpha - $table_alpha) < 0.1 * $sigma"
check "c_hat equals the table's to 1e-3" "abs($c - $table_c) < 1e-3"
finish
