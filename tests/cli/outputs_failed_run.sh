#!/usr/bin/env bash
# A failed run leaves --out as it was (docs/cli.md: exit 1 writes nothing), and two runs never
# write to one --out at once (the second waits for the first).
#   outputs_failed_run.sh SEDWAVE OBSERVATIONS
# The failure is a full disk for the last output: observations.csv is made a link to /dev/full
# (written in place, never replaced), so fit.json and curves.csv are written before it fails.
set -uo pipefail
sedwave="$1"; obs="$2"
dir="$(mktemp -d)"; trap 'rm -rf "$dir"' EXIT
out="$dir/fit"
fail() { echo "FAILED: $*"; exit 1; }
"$sedwave" invert "$obs" --method ceres --no-plot --out "$out" > "$dir/log" 2>&1; code=$?
[ "$code" -eq 0 ] || [ "$code" -eq 3 ] || fail "first run exited $code: $(cat "$dir/log")"  # 3: flagged, written
before=$(md5sum "$out/fit.json" "$out/curves.csv")
rm "$out/observations.csv"; ln -s /dev/full "$out/observations.csv"
"$sedwave" invert "$obs" --method ceres --fit kappa,gamma --d 2e-4 --no-plot --out "$out" > "$dir/log" 2>&1
code=$?
[ "$code" -eq 1 ] || fail "a run that cannot write observations.csv exited $code: $(cat "$dir/log")"
grep -q "cannot write .*observations.csv" "$dir/log" || fail "no error naming observations.csv: $(cat "$dir/log")"
[ "$(md5sum "$out/fit.json" "$out/curves.csv")" = "$before" ] || fail "the failed run replaced fit.json or curves.csv"
ls -a "$out" | grep -q '\.tmp-' && fail "the failed run left temporaries: $(ls -a "$out")"
[ -c /dev/full ] || fail "/dev/full is no longer a character device"

# A second run on the same --out while another holds its lock: it says so and waits, then runs.
rm "$out/observations.csv"
exec 9> "$out/.sedwave.lock"; flock -n 9 || fail "cannot take the lock for the test"
"$sedwave" invert "$obs" --method ceres --no-plot --out "$out" 9>&- > "$dir/log" 2>&1 & second=$!
sleep 1
kill -0 "$second" 2>/dev/null || fail "the second writer did not wait: $(cat "$dir/log")"
grep -q -- "--out $out: another sedwave run is writing there. waiting" "$dir/log" || fail "no lock message: $(cat "$dir/log")"
[ -e "$out/observations.csv" ] && fail "the second writer wrote while the lock was held"
exec 9>&-
wait "$second"; code=$?
[ "$code" -eq 0 ] || [ "$code" -eq 3 ] || fail "the second writer exited $code after the lock was released"
[ -f "$out/observations.csv" ] || fail "the second writer wrote nothing after the lock was released"
echo "ok: a failed run left the previous outputs; a second writer waited for the first"
