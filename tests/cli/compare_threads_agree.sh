#!/usr/bin/env bash
# `sedwave compare` on 1 thread and on the default thread count (OMP_NUM_THREADS=3 here: more
# threads than jobs at a time, so that jobs finish in another order) writes the same results:
# compare.json without its wall times, and every CSV, byte for byte. The same two runs check what a
# user sees: the ranking line, the posterior bands named, and (on the run with plots) the plots.
# Biot-Stoll's evidence comes from adaptive cubature (importance sampling refuses it), EDFM's from
# importance sampling: both methods' thread counts are checked.
#   compare_threads_agree.sh SEDWAVE OBSERVATIONS OUTDIR
set -euo pipefail
sedwave="$1"; obs="$2"; out="$3"
rm -rf "$out"
run() {  # DIR, then extra options
  local dir="$1" code=0; shift
  "$sedwave" compare "$obs" --models edfm,grain-shearing,biot-stoll --steps 400 --temperatures 16 --out "$dir" "$@" \
    > "$dir.log" 2>&1 || code=$?
  [ "$code" -eq 0 ] || [ "$code" -eq 3 ] || { echo "FAILED: compare $* exited $code"; cat "$dir.log"; exit 1; }
}
mkdir -p "$out"
run "$out/one" --threads 1 --no-plot
OMP_NUM_THREADS=3 run "$out/default"
expect_line() {  # LOG, extended regular expression
  grep -Eq -- "$2" "$1" || { echo "FAILED: no line /$2/ in $1:"; cat "$1"; exit 1; }
}
expect_line "$out/one.log" "^biot-stoll is preferred over edfm by a factor"
expect_line "$out/one.log" "^1 +biot-stoll .* AC/AC "
expect_line "$out/one.log" "^2 +edfm .* IS/IS "
expect_line "$out/one.log" "^posterior bands: .*/predictive_\*\.csv"
expect_line "$out/default.log" "^plot written to .*/predictive\.png and predictive\.svg"
strip() { python3 -c '
import json, sys
def drop(x):
    if isinstance(x, dict): return {k: drop(v) for k, v in x.items() if k != "wall_seconds"}
    if isinstance(x, list): return [drop(v) for v in x]
    return x
print(json.dumps(drop(json.load(open(sys.argv[1]))), sort_keys=True))' "$1"; }
[ "$(strip "$out/one/compare.json")" = "$(strip "$out/default/compare.json")" ] \
  || { echo "FAILED: compare.json differs between 1 and 3 threads"; exit 1; }
for f in "$out"/one/*.csv; do
  cmp -s "$f" "$out/default/$(basename "$f")" || { echo "FAILED: $(basename "$f") differs between 1 and 3 threads"; exit 1; }
done
echo "ok: 1 and 3 threads wrote the same compare.json (wall times aside) and $(ls "$out"/one/*.csv | wc -l) identical CSVs"
