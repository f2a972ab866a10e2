#!/usr/bin/env bash
# Example 01: invert a digitised figure.
#
# A published attenuation curve, digitised with WebPlotDigitizer, is fitted with the 1D lattice
# (grain-contact chain) model. The grain diameter is fixed at a value a core sample would give;
# the contact stiffness kappa and dashpot gamma are fitted. The point of the example is what the
# report says: which parameters and combinations the points determine, and which results it
# flags as implausible, and why.
#
#   examples/01-digitized-figure/run.sh [SEDWAVE [OUT]]
source "$(dirname "$0")/../common.sh"

step "The input: a two-column WebPlotDigitizer export (kHz, dB/m), no units in the file itself"
# data/digitized/README.md says what the columns hold; the units go on the command line.
head -3 "$DATA/digitized/example_webplotdigitizer.csv"

step "Fit kappa and gamma, d fixed at 0.2 mm"
# --digitized QUANTITY:FREQUENCY_UNIT:VALUE_UNIT:RELATIVE_SIGMA describes the file: attenuation in
#   dB/m against kHz, each point given a 10 % (1 sigma) error.
# --water-speed gives the water sound speed the report uses for speed ratios.
# --fit kappa,gamma frees those two; --d 2e-4 fixes the grain diameter [m].
# --no-plot skips gnuplot; fit.json holds everything the screen shows, and more.
# Exit status 3: the fit finished, but a result is flagged (see below).
run 3 "$SEDWAVE" invert --digitized-file "$DATA/digitized/example_webplotdigitizer.csv" \
    --digitized attenuation:kHz:dB/m:0.1 --water-speed 1500 \
    --fit kappa,gamma --d 2e-4 --no-plot --out fit

step "What the fit determined"
# Six attenuation points from 0.1 to 1 kHz follow one power law, f^1.8. The chain reproduces them
# (chi2/nu below 1), but attenuation alone fixes only the time scales: tau = gamma/kappa, the
# contact's relaxation time, sets where alpha bends from f^2 towards f^1/2. With no sound speed in
# the data, kappa is driven to whatever makes that bend fit, and the implied low-frequency sound
# speed c0 comes out around 50 km/s, far outside any sediment's. The report flags c0, gamma_hat
# and kappa/kappa_Hertz, each with its likely cause; this is why the exit status is 3.
result chi2_per_dof   "$(json fit/fit.json "['reduced_chi2']")"
result tau_s          "$(json fit/fit.json "['combinations']['tau']['value']")"
result f_star_Hz      "$(json fit/fit.json "['combinations']['f_star']['value']")"
result c0_m_per_s     "$(json fit/fit.json "['combinations']['c0']['value']")"
check "the report flags c0 as outside the physical range" \
      "'c0' in [f['quantity'] for f in __import__('json').load(open('fit/fit.json'))['flags']]"
check "gamma alone is not determined (its profile is what the report gives)" \
      "not __import__('json').load(open('fit/fit.json'))['parameters']['gamma']['identifiable']"
check "kappa is determined" \
      "__import__('json').load(open('fit/fit.json'))['parameters']['kappa']['identifiable']"

# What to do about it: add sound-speed points (examples/02 plans such a measurement), or use a
# model whose speed comes from the pore water (sedwave models; docs/models/README.md).
finish
