#!/usr/bin/env bash
# `sedwave compare` of the lattice against EDFM on data EDFM made (the lattice's chi^2 in the
# thousands): the lattice's ln Z is printed as an upper bound, "<= -chi^2/2", labelled UB and
# explained, never as an estimate with an error, and the run counts as complete (exit 0).
#   compare_states_a_bound.sh SEDWAVE OUTDIR
set -euo pipefail
sedwave="$1"; out="$2"
rm -rf "$out"; mkdir -p "$out"
"$sedwave" synthesize --model edfm --set porosity=0.42 --set permeability=3e-11 --from 100 --to 1e5 --points 12 \
  --alpha-noise 0.02 --speed-noise 0.003 --seed 7 --out "$out/edfm.csv" > "$out/synthesize.log" 2>&1
code=0
"$sedwave" compare "$out/edfm.csv" --models lattice,edfm --no-plot --out "$out/compare" > "$out/compare.log" 2>&1 || code=$?
[ "$code" -eq 0 ] || { echo "FAILED: compare exited $code"; cat "$out/compare.log"; exit 1; }
expect_line() {  # extended regular expression
  grep -Eq -- "$1" "$out/compare.log" || { echo "FAILED: no line /$1/ in:"; cat "$out/compare.log"; exit 1; }
}
expect_line "^1 +edfm .* IS/IS "
expect_line "^2 +lattice .* <= -[0-9.]+ .* UB/UB .*\(ln Z: an upper bound\)$"
expect_line "^UB: an upper bound, ln Z <= the best fit's ln L"
expect_line "^lattice, ln Z by upper bound: "
expect_line "^edfm is preferred over lattice by a factor of at least e\^"
python3 - "$out/compare/compare.json" <<'PY'
import json, sys
lattice = next(m for m in json.load(open(sys.argv[1])) if m["model"] == "lattice")
for column in ("evidence", "evidence_priors_widened_x10"):
    e = lattice[column]
    assert e["method"] == "upper bound" and not e["converged"], e
    assert e["log_evidence"] == -0.5 * lattice["chi2"], (e["log_evidence"], lattice["chi2"])
PY
echo "compare states the lattice's bound"
