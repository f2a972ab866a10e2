#!/usr/bin/env bash
# Two tables sharing one --packing that does not exist yet (docs/tables.md, "One packing for several
# tables"): while this script holds the packing's lock, both runs say they are waiting; once it lets
# go, one of them prepares and saves the packing while the other waits again, then reads it instead
# of preparing its own. So exactly one prepares, and both tables give the same numbers.
#
# Usage: shared_packing.sh SEDWAVE SCENE GRID WORK_DIR
set -uo pipefail
sedwave=$1 scene=$2 grid=$3 work=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
# A shorter column than the scene's: a few seconds of preparation.
sed "s/^grains = 2000\s*$/grains = 300/" "$scene" > "$(basename "$scene")"
cp "$grid" grid.toml
exec 9> shared.packing.h5.lock
flock -n 9 || fail "cannot take the lock for the test"
run=(table grid.toml --engine long_wavelength --packing shared.packing.h5)
"$sedwave" "${run[@]}" --out first.h5 9>&- > first.log 2>&1 & first=$!
"$sedwave" "${run[@]}" --out second.h5 9>&- > second.log 2>&1 & second=$!
waiting="waiting while another process prepares or writes shared.packing.h5"
for _ in $(seq 600); do
  grep -q "$waiting" first.log && grep -q "$waiting" second.log && break
  sleep 0.1
done
grep -q "$waiting" first.log && grep -q "$waiting" second.log ||
  fail "the runs did not both wait for the lock: $(cat first.log second.log)"
exec 9>&-
wait "$first" || fail "the first run failed: $(cat first.log)"
wait "$second" || fail "the second run failed: $(cat second.log)"
prepared=$(grep -l "prepare: compressed" first.log second.log | wc -l)
[[ $prepared -eq 1 ]] || fail "$prepared runs prepared a packing (expected 1): $(cat first.log second.log)"
values() { "$sedwave" show "$1" | grep -v '^#' | cut -d, -f1-7; }
[[ "$(values first.h5)" == "$(values second.h5)" ]] || fail "the two tables differ: $(values first.h5) / $(values second.h5)"
echo "PASS: both runs waited; one prepared the packing, the other read it; the same numbers"
