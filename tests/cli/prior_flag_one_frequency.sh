#!/usr/bin/env bash
# Ten identical attenuation rows at one frequency leave kappa, d and gamma on a curved surface through
# the default priors' box: the data place none of them nor any combination, and the posterior must
# say so for each (PRIOR-CONTROLLED), gamma, tau, f* and gamma_hat included, whose intervals span
# most of their priors' decades while the data's information at one draw sees them narrowed.
#   prior_flag_one_frequency.sh SEDWAVE OBSERVATIONS
set -uo pipefail
sedwave="$1"; obs="$2"
dir="$(mktemp -d)"; trap 'rm -rf "$dir"' EXIT
fail() { echo "FAILED: $*"; exit 1; }
"$sedwave" invert "$obs" --method posterior --steps 200 --no-plot --out "$dir/fit" > "$dir/log" 2>&1; code=$?
[ "$code" -eq 0 ] || [ "$code" -eq 3 ] || fail "invert exited $code: $(cat "$dir/log")"
table="$(sed -n '/^  quantity  /,/^  converged\|^  NOT CONVERGED/p' "$dir/log")"
for q in kappa d gamma c0 tau f_star gamma_hat kappa_over_hertz; do
  line="$(grep -E "^  $q " <<< "$table")" || fail "no posterior line for $q: $table"
  grep -q "PRIOR-CONTROLLED" <<< "$line" || fail "$q is not flagged: $line"
done
echo "ok: every quantity flagged PRIOR-CONTROLLED"
