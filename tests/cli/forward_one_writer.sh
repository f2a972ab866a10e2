#!/usr/bin/env bash
# Two `sedwave forward` runs with one --out never both write it: while another holds the file's lock
# (.NAME.lock beside it), a run says so and waits, writing nothing; once the lock is free it runs.
#   forward_one_writer.sh SEDWAVE SCENE
set -uo pipefail
sedwave="$1"; scene="$2"
dir="$(mktemp -d)"; trap 'rm -rf "$dir"' EXIT
fail() { echo "FAILED: $*"; exit 1; }
out="$dir/run.h5"
exec 9> "$dir/.run.h5.lock"; flock -n 9 || fail "cannot take the lock for the test"
"$sedwave" forward "$scene" --out "$out" 9>&- > "$dir/log" 2>&1 & second=$!
for _ in $(seq 100); do
  grep -q -- "--out $out: another sedwave run is writing there. waiting" "$dir/log" && break
  sleep 0.1
done
grep -q -- "--out $out: another sedwave run is writing there. waiting" "$dir/log" || fail "no lock message: $(cat "$dir/log")"
sleep 0.5
kill -0 "$second" 2>/dev/null || fail "the second writer did not wait: $(cat "$dir/log")"
[ -e "$out" ] && fail "the second writer wrote while the lock was held"
exec 9>&-
wait "$second"; code=$?
[ "$code" -eq 0 ] || [ "$code" -eq 3 ] || fail "the run exited $code after the lock was released: $(cat "$dir/log")"
[ -f "$out" ] || fail "the run wrote nothing after the lock was released"
grep -q "written to $out" "$dir/log" || fail "no 'written to' line: $(cat "$dir/log")"
echo "ok: a second forward run on one --out waited for the first"
