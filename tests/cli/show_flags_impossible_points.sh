#!/usr/bin/env bash
# `sedwave show` names a point stored as ok whose values cannot be (NaN, a negative attenuation,
# a speed <= 0) and exits 3. The table is a copy of a shipped one with the first ok point's
# alpha_hat overwritten by NaN and its c_hat by -1 (raw data: HDF5 checksums only its metadata).
#   show_flags_impossible_points.sh SEDWAVE TABLE
set -uo pipefail
sedwave="$1"; table="$2"
dir="$(mktemp -d)"; trap 'rm -rf "$dir"' EXIT
fail() { echo "FAILED: $*"; exit 1; }
"$sedwave" show "$table" > "$dir/before.csv" || fail "the shipped table does not show cleanly"
python3 - "$table" "$dir/before.csv" "$dir/broken.h5" <<'PY' || fail "cannot make the broken table"
import csv, math, struct, sys
table, shown, broken = sys.argv[1:4]
rows = [r for r in csv.DictReader(l for l in open(shown) if not l.startswith('#')) if r['status'] == 'ok']
data = bytearray(open(table, 'rb').read())
for key, new in (('alpha_hat', math.nan), ('c_hat', -1.0)):
    old = struct.pack('<d', float(rows[0][key]))
    assert data.count(old) == 1, key
    at = data.find(old)
    data[at:at + 8] = struct.pack('<d', new)
open(broken, 'wb').write(bytes(data))
PY
"$sedwave" show "$dir/broken.h5" > "$dir/out.csv" 2> "$dir/err"; code=$?
[ "$code" -eq 3 ] || fail "exit $code for a table with impossible ok points: $(cat "$dir/err")"
grep -q "is stored as ok but alpha_hat = nan" "$dir/err" || fail "no flag naming the point: $(cat "$dir/err")"
grep -q "1 point(s) stored as ok hold impossible values" "$dir/err" || fail "no summary: $(cat "$dir/err")"
echo "ok: $(head -1 "$dir/err")"
