#!/usr/bin/env bash
# Example 04: a small dispersion table, and a fit with it.
#
# A dispersion table holds alpha_hat and c_hat of a 3D packing on a grid of (omega_hat,
# gamma_hat); `sedwave invert --model table:FILE.h5` then fits field data with the packing's own
# dispersion instead of the 1D chain's. Field frequencies (50 Hz - 1 kHz) lie far below what a
# driven channel can resolve, so this table uses the long-wavelength engine: the packing's
# omega_hat -> 0 limit at fixed omega_hat * gamma_hat (docs/tables.md, "Field frequencies").
# The example builds a 6 x 7 table from ONE shipped 10^4-grain packing, fits the shipped field
# data with it, and compares with the shipped table of FIVE packings.
#
#   examples/04-table-fit/run.sh [SEDWAVE [OUT]]
source "$(dirname "$0")/../common.sh"

step "The scene and the grid"
# The shipped scene data/scenes/field_w3.toml is an ensemble of five packings; this copy uses the
# first only (ensemble = 1), which makes the table five times faster to fill.
sed 's/^ensemble = 5/ensemble = 1/' "$DATA/scenes/field_w3.toml" > field_w3_one.toml
grep '^ensemble' field_w3_one.toml
# The grid: 6 log-spaced omega_hat and 7 log-spaced gamma_hat, covering the field data for
# kappa 1e6 - 1e7 N/m, gamma 0.5 - 50 kg/s and d = 0.3 mm (the bounds of the fit below).
cat > grid.toml <<'TOML'
scene = "field_w3_one.toml"                       # relative to this file
omega_hat = { from = 1e-5, to = 3e-3, points = 6 }
gamma_hat = { from = 0.5, to = 500, points = 7 }
TOML
cat grid.toml

step "Fill the table (42 points) from the shipped packing"
# --packing names the prepared packing (member k of an ensemble is FILE.member<k>.h5).
# Under `mpirun -np P` the points are shared among P ranks (examples/06). A killed run resumes
# when the same command is given again (examples/07).
run 0 "$SEDWAVE" table grid.toml --engine long_wavelength \
    --packing "$DATA/tables/field_w3.packing.h5" --out one_packing.h5 --quiet
"$SEDWAVE" show one_packing.h5 | sed -n 1,8p
check "all 42 points are ok" "$("$SEDWAVE" show --values-only one_packing.h5 | grep -c ',ok,') == 42"

step "Fit the shipped field data with the table"
# --d fixes the grain diameter (the table's dispersion is in units of d); kappa and gamma are
# fitted inside bounds where the table has values. Exit 3: kappa comes out about 35 x the Hertz
# stiffness of quartz contacts, which the report flags: this dry frame has to carry the stiffness
# that the pore water carries in a real seabed (docs/models/README.md).
FIT="--fit kappa,gamma --d 3e-4 --kappa-bounds 1e6,1e7 --gamma-bounds 0.5,50 --kappa 2.5e6 --gamma 5 --no-plot"
run 3 "$SEDWAVE" invert "$DATA/field/zhou2009_regression.csv" --model table:one_packing.h5 $FIT --out fit_one
result one_kappa_N_per_m "$(json fit_one/fit.json "['parameters']['kappa']['value']")"
result one_gamma_kg_per_s "$(json fit_one/fit.json "['parameters']['gamma']['value']")"
result one_chi2_per_dof "$(json fit_one/fit.json "['reduced_chi2']")"

step "The same fit with the shipped table of five packings (561 points)"
run 3 "$SEDWAVE" invert "$DATA/field/zhou2009_regression.csv" \
    --model table:"$DATA/tables/field_w3_long_wavelength.h5" $FIT --out fit_five
result five_kappa_N_per_m "$(json fit_five/fit.json "['parameters']['kappa']['value']")"
result five_gamma_kg_per_s "$(json fit_five/fit.json "['parameters']['gamma']['value']")"
result five_chi2_per_dof "$(json fit_five/fit.json "['reduced_chi2']")"
# One packing carries its own disorder (its low-frequency damping differs from the others' by tens
# of per cent: docs/tables.md, "What a table's σ includes, and how many packings you need"); the five-packing mean describes
# the data far better. Both agree on the stiffness to a few per cent: the sound speed fixes it.
check "the five-packing table fits better than the one-packing table" \
      "$(json fit_five/fit.json "['chi2']") < $(json fit_one/fit.json "['chi2']")"
check "both put kappa above 10 x Hertz, and the report flags it" \
      "all('kappa_over_hertz' in [f['quantity'] for f in __import__('json').load(open(d + '/fit.json'))['flags']] for d in ('fit_one', 'fit_five'))"
finish
