#!/usr/bin/env bash
# Example 02: plan a measurement, then invert the synthetic data.
#
# Before going to sea: would attenuation and sound speed from 10 kHz to 1 MHz determine the
# grain-contact parameters of a medium sand? `sedwave synthesize` writes what the lattice model
# predicts for a chosen truth, with the noise the inversion assumes; `sedwave invert` fits it
# back. The answer here: the band determines the sound speed c0 and the relaxation time
# tau = gamma/kappa, but not kappa, d and gamma one by one. With d fixed from a core sample, kappa
# and gamma are determined and the truth lies inside their intervals.
#
#   examples/02-plan-a-measurement/run.sh [SEDWAVE [OUT]]
source "$(dirname "$0")/../common.sh"

# The truth: kappa = 7e5 N/m, d = 0.3 mm, gamma = 5 kg/s (quartz grains, rho_s = 2650 kg/m^3).
KAPPA=7e5 D=3e-4 GAMMA=5

step "Synthesize the planned data: 15 frequencies, 10 % attenuation and 1 % speed errors"
# --alpha-noise / --speed-noise: relative 1-sigma noise, also written as each point's sigma.
# --seed makes the noise reproducible. The CSV's header records the truth and says SYNTHETIC.
run 0 "$SEDWAVE" synthesize --model lattice --kappa $KAPPA --d $D --gamma $GAMMA \
    --from 1e4 --to 1e6 --points 15 --alpha-noise 0.1 --speed-noise 0.01 --seed 2 --out planned.csv
grep '^#' planned.csv

step "Fit all three contact parameters"
# Exit 3: d runs to its search bound, which the report flags (the bound, not the data, holds it).
run 3 "$SEDWAVE" invert planned.csv --model lattice --fit kappa,d,gamma --no-plot --out fit_free
# The true c0 = d sqrt(kappa/m), m = rho_s pi d^3/6, and tau = gamma/kappa:
python3 - <<PY | tee truth.txt
import math
m = 2650 * math.pi * $D**3 / 6
print("true c0  [m/s]", $D * math.sqrt($KAPPA / m))
print("true tau [s]  ", $GAMMA / $KAPPA)
PY
result free_c0_m_per_s  "$(json fit_free/fit.json "['combinations']['c0']['value']")"
result free_tau_s       "$(json fit_free/fit.json "['combinations']['tau']['value']")"
result free_chi2_per_dof "$(json fit_free/fit.json "['reduced_chi2']")"
check "d is not determined by this band" \
      "not __import__('json').load(open('fit_free/fit.json'))['parameters']['d']['identifiable']"
check "c0 and tau are determined" \
      "all(__import__('json').load(open('fit_free/fit.json'))['combinations'][k]['determined'] for k in ('c0', 'tau'))"

step "Fix d at the core sample's 0.3 mm and fit kappa and gamma"
run 0 "$SEDWAVE" invert planned.csv --model lattice --fit kappa,gamma --d $D --no-plot --out fit_d_known
result known_d_kappa_N_per_m "$(json fit_d_known/fit.json "['parameters']['kappa']['value']")"
result known_d_gamma_kg_per_s "$(json fit_d_known/fit.json "['parameters']['gamma']['value']")"
result known_d_chi2_per_dof "$(json fit_d_known/fit.json "['reduced_chi2']")"
# The truth must lie inside each parameter's 95 % interval (about 2 sigma of ln value): a check
# that fails if the fit, the model or the noise model is wrong.
for p in kappa gamma; do
  truth=$([ $p = kappa ] && echo $KAPPA || echo $GAMMA)
  check "true $p inside 2 sigma of the fit" \
        "(lambda q: abs(__import__('math').log(q['value'] / $truth)) < 2 * q['log_sigma'])(__import__('json').load(open('fit_d_known/fit.json'))['parameters']['$p'])"
done
check "chi2/nu below 2 (the model describes its own synthetic data)" \
      "__import__('json').load(open('fit_d_known/fit.json'))['reduced_chi2'] < 2"
finish
