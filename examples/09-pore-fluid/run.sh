#!/usr/bin/env bash
# Example 09: a still pore fluid around the grains, in both engines, on one packing.
#
# The scene's [fluid] section puts a squeeze film between every two grains closer than a cut-off
# gap and drag on every grain (docs/fluid.md). The packing is prepared dry (viscous forces vanish at
# rest), so the dry and the wet runs share the shipped 1000-grain packing. Each engine runs dry and
# wet at the same point; the two engines must agree wet as closely as they agree dry, and the fluid
# must add attenuation.
#
#   examples/09-pore-fluid/run.sh [SEDWAVE [OUT]]
source "$(dirname "$0")/../common.sh"

PACKING=$DATA/tables/thesis_w3_small.packing.h5
W=0.4 G=0.3

step "Four scenes: two engines, dry and wet"
# The fluid: mu_hat = mu d / sqrt(kappa m) = 2e-4 (a fluid forty times as viscous, relative to the
# contacts, as water around 0.3 mm sand), roughness 1e-3 d, cut-off 0.05 d, Richardson-Zaki drag at
# the packing's porosity. Both engines fit the layers 2 .. 25 d from the driven wall.
for engine in time_domain linear; do
  small_channel_scene $engine > ${engine}_dry.toml
  { cat ${engine}_dry.toml
    printf '\n[fluid]\nviscosity = 2e-4\nroughness = 1e-3\ncutoff = 0.05\n'
  } > ${engine}_wet.toml
done

for engine in time_domain linear; do
  for fluid in dry wet; do
    step "$engine, $fluid"
    run 0 "$SEDWAVE" forward ${engine}_$fluid.toml --packing "$PACKING" --omega-hat $W --gamma-hat $G \
        --out ${engine}_$fluid.h5 | tee ${engine}_$fluid.log
  done
done

step "The same point as a table, both engines"
# A table records its fluid (attribute pore_fluid, printed by show) and holds its groups fixed.
for engine in time_domain linear; do
  printf 'scene = "%s_wet.toml"\nomega_hat = [%s]\ngamma_hat = [%s]\n' $engine $W $G > ${engine}_grid.toml
  run 0 "$SEDWAVE" table ${engine}_grid.toml --engine $engine --packing "$PACKING" --out ${engine}_table.h5 --quiet
  run 0 "$SEDWAVE" show ${engine}_table.h5 | tee ${engine}_table.csv
done

# alpha_hat, its sigma, c_hat and its sigma from each run's result line.
fit() { sed -n 's/^alpha_hat \(\S*\) +- \(\S*\) *c_hat \(\S*\) +- \(\S*\) .*/\1 \2 \3 \4/p' "$1"; }
read -r a_dd s_dd c_dd sc_dd <<<"$(fit time_domain_dry.log)"
read -r a_ld s_ld c_ld sc_ld <<<"$(fit linear_dry.log)"
read -r a_dw s_dw c_dw sc_dw <<<"$(fit time_domain_wet.log)"
read -r a_lw s_lw c_lw sc_lw <<<"$(fit linear_wet.log)"
# The fluid's two dashpots, as forward prints them (in sqrt(kappa m), beside gamma_hat = 0.3).
read -r film drag <<<"$(sed -n 's/.*film at the roughness \(\S*\) .*drag \(\S*\) per grain.*/\1 \2/p' linear_wet.log)"
result film_dashpot "$film"
result drag_dashpot "$drag"
result dem_dry_alpha_hat "$a_dd"
result linear_dry_alpha_hat "$a_ld"
result dem_wet_alpha_hat "$a_dw"
result dem_wet_c_hat "$c_dw"
result linear_wet_alpha_hat "$a_lw"
result linear_wet_c_hat "$c_lw"
table_alpha() { tail -1 "$1" | cut -d, -f4; }
check "both tables record the fluid" "$(cat time_domain_table.csv linear_table.csv | grep -c '^# pore fluid: mu_hat 0.0002, roughness 0.001 d, cutoff 0.05 d') == 2"
check "the tables' points are the forward runs' (time domain; forward prints 6 digits)" "abs($(table_alpha time_domain_table.csv) - $a_dw) < 1e-6"
check "the tables' points are the forward runs' (linear; forward prints 6 digits)" "abs($(table_alpha linear_table.csv) - $a_lw) < 1e-6"
check "wet alpha_hat: engines within one combined sigma" "abs($a_dw - $a_lw) < ($s_dw**2 + $s_lw**2)**0.5"
check "wet c_hat: engines within one combined sigma" "abs($c_dw - $c_lw) < ($sc_dw**2 + $sc_lw**2)**0.5"
check "engines agree wet about as well as dry (within 2x the dry difference plus a tenth of a sigma)" \
      "abs($a_dw - $a_lw) <= 2 * abs($a_dd - $a_ld) + 0.1 * $s_lw"
check "the fluid adds attenuation: wet alpha_hat above dry by three sigma (linear engine)" \
      "$a_lw - $a_ld > 3 * ($s_lw**2 + $s_ld**2)**0.5"
finish
