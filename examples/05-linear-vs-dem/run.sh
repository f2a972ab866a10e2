#!/usr/bin/env bash
# Example 05: the linear-response engine against the time-domain (DEM) engine on one packing.
#
# The drive is tiny (A = 1e-4 d), so the grains obey the linearised equations of motion about the
# compressed static state; the linear engine solves for their steady response in one sparse
# complex solve instead of integrating some 10^4 time steps (docs/linear.md). Both engines drive
# the same shipped 1000-grain packing at the same point and fit the same layers; they must agree
# within their errors. The 1D lattice theory at the same point shows what the 3D packing adds.
#
#   examples/05-linear-vs-dem/run.sh [SEDWAVE [OUT]]
source "$(dirname "$0")/../common.sh"

PACKING=$DATA/tables/thesis_w3_small.packing.h5
W=0.4 G=0.3

step "Two scenes that differ only in the engine"
# The shipped scene of the small table, with `engine` set at the top. Both fit the layers
# 2 .. 25 d from the driven wall (max_fit_depth); [linear] ensemble = 1: one packing (the linear
# engine can average several: docs/linear.md). small_channel_scene in ../common.sh writes them.
for engine in time_domain linear; do
  small_channel_scene $engine > $engine.toml
done
diff time_domain.toml linear.toml || true

step "Time-domain engine: integrate until echoes could return, lock in, fit"
run 0 "$SEDWAVE" forward time_domain.toml --packing "$PACKING" --omega-hat $W --gamma-hat $G --out dem.h5 | tee dem.log

step "Linear engine: one complex solve"
# It also counts, over a ladder of amplitudes, the contacts that would open (or gaps close) in a
# cycle: where that count is no longer small, the linearisation stops being exact.
run 0 "$SEDWAVE" forward linear.toml --packing "$PACKING" --omega-hat $W --gamma-hat $G --out linear.h5 | tee linear.log

step "The 1D lattice at the same point (no disorder, no scattering)"
run 0 "$SEDWAVE" theory --model lattice --omega-hat $W --gamma-hat $G | tee theory.csv

# Pull alpha_hat, its sigma, c_hat and its sigma from each run's last result line.
read -r a_dem s_dem c_dem sc_dem <<<"$(sed -n 's/^alpha_hat \(\S*\) +- \(\S*\) *c_hat \(\S*\) +- \(\S*\) .*/\1 \2 \3 \4/p' dem.log)"
read -r a_lin s_lin c_lin sc_lin <<<"$(sed -n 's/^alpha_hat \(\S*\) +- \(\S*\) *c_hat \(\S*\) +- \(\S*\) .*/\1 \2 \3 \4/p' linear.log)"
a_1d=$(tail -1 theory.csv | cut -d, -f4)
result dem_alpha_hat "$a_dem"
result dem_c_hat "$c_dem"
result linear_alpha_hat "$a_lin"
result linear_c_hat "$c_lin"
result lattice_alpha_hat "$a_1d"
check "alpha_hat: engines within one combined sigma" "abs($a_dem - $a_lin) < ($s_dem**2 + $s_lin**2)**0.5"
check "c_hat: engines within one combined sigma" "abs($c_dem - $c_lin) < ($sc_dem**2 + $sc_lin**2)**0.5"
# The packing attenuates several times more than the chain at the same omega_hat and gamma_hat:
# its disorder scatters and its non-affine motion works the dashpots harder.
check "the 3D packing attenuates more than the 1D chain" "$a_lin > 2 * $a_1d"
finish
