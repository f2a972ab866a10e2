#!/usr/bin/env bash
# A failed run leaves --out as it was (docs/cli.md: exit 1 writes nothing), and two runs never
# write to one --out at once.
#   outputs_failed_run.sh SEDWAVE OBSERVATIONS
# The failure is a full disk for the last output: observations.csv is made a link to /dev/full
# (written in place, never replaced), so fit.json and curves.csv are written before it fails.
set -uo pipefail
sedwave="$1"; obs="$2"
dir="$(mktemp -d)"; trap 'rm -rf "$dir"' EXIT
out="$dir/fit"
fail() { echo "FAILED: $*"; exit 1; }
"$sedwave" invert "$obs" --method ceres --no-plot --out "$out" > "$dir/log" 2>&1 || fail "first run: $(cat "$dir/log")"
before=$(md5sum "$out/fit.json" "$out/curves.csv")
rm "$out/observations.csv"; ln -s /dev/full "$out/observations.csv"
"$sedwave" invert "$obs" --method ceres --fit kappa,gamma --d 2e-4 --no-plot --out "$out" > "$dir/log" 2>&1
code=$?
[ "$code" -eq 1 ] || fail "a run that cannot write observations.csv exited $code: $(cat "$dir/log")"
grep -q "cannot write .*observations.csv" "$dir/log" || fail "no error naming observations.csv: $(cat "$dir/log")"
[ "$(md5sum "$out/fit.json" "$out/curves.csv")" = "$before" ] || fail "the failed run replaced fit.json or curves.csv"
ls -a "$out" | grep -q '\.tmp-' && fail "the failed run left temporaries: $(ls -a "$out")"
[ -c /dev/full ] || fail "/dev/full is no longer a character device"

# A second run on the same --out while one holds its lock: refused, naming the directory.
rm "$out/observations.csv"
flock -o "$out/.sedwave.lock" sleep 20 & holder=$!
sleep 0.5
"$sedwave" invert "$obs" --method ceres --no-plot --out "$out" > "$dir/log" 2>&1; code=$?
kill "$holder" 2>/dev/null; wait "$holder" 2>/dev/null
[ "$code" -eq 1 ] || fail "a second writer to one --out exited $code: $(cat "$dir/log")"
grep -q -- "--out $out: another sedwave run is writing there" "$dir/log" || fail "no lock message: $(cat "$dir/log")"
echo "ok: a failed run left the previous outputs; a second writer was refused"
