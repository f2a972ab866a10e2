#!/usr/bin/env bash
# Outputs given as a FIFO, a device, a symbolic link or /dev/stdout (docs/cli.md, "Where outputs
# go"): text is written in place or through the link; HDF5 (which must seek) is refused with a
# clear error; nothing is ever replaced but a regular file. Everything lives in a fresh temporary
# directory; /dev/null is only written to, /dev/full only read from as a target that must stay.
#   outputs_land_safely.sh SEDWAVE SCENE_DATA_DIR
set -uo pipefail
sedwave="$1"; scene_data="$2"
dir="$(mktemp -d)"; trap 'rm -rf "$dir"' EXIT
fail() { echo "FAILED: $*"; exit 1; }
synth=(synthesize --model edfm --set porosity=0.42 --set permeability=3e-11 --from 100 --to 1e5 --points 4)

# A FIFO: the CSV arrives through it, and it stays a FIFO.
mkfifo "$dir/pipe"
cat "$dir/pipe" > "$dir/from_pipe.csv" & reader=$!
"$sedwave" "${synth[@]}" --out "$dir/pipe" > "$dir/log" 2>&1 || fail "synthesize to a FIFO: $(cat "$dir/log")"
wait "$reader"
[ -p "$dir/pipe" ] || fail "the FIFO was replaced"
grep -q "^# data_kind: SYNTHETIC" "$dir/from_pipe.csv" || fail "nothing came through the FIFO"

# /dev/null: written in place, still a character device; /dev/full: an error, still a device.
"$sedwave" "${synth[@]}" --out /dev/null > "$dir/log" 2>&1 || fail "synthesize to /dev/null: $(cat "$dir/log")"
[ -c /dev/null ] || fail "/dev/null is no longer a character device"
if "$sedwave" "${synth[@]}" --out /dev/full > "$dir/log" 2>&1; then fail "synthesize to /dev/full exited 0"; fi
grep -q "cannot write /dev/full" "$dir/log" || fail "no error naming /dev/full: $(cat "$dir/log")"
[ -c /dev/full ] || fail "/dev/full is no longer a character device"

# /dev/stdout into a pipe.
lines=$("$sedwave" "${synth[@]}" --out /dev/stdout 2>/dev/null | grep -c '^attenuation\|^sound_speed' || true)
[ "$lines" -ge 8 ] || fail "--out /dev/stdout gave $lines data rows"

# A symbolic link to a file: the file is rewritten, the link stays.
echo old > "$dir/real.csv"; ln -s real.csv "$dir/link.csv"
"$sedwave" "${synth[@]}" --out "$dir/link.csv" > "$dir/log" 2>&1 || fail "synthesize through a link: $(cat "$dir/log")"
[ -L "$dir/link.csv" ] || fail "the symbolic link was replaced"
grep -q "SYNTHETIC" "$dir/real.csv" || fail "the link's target was not written"

# HDF5 outputs refuse a FIFO and a device before any work, and leave them as they were.
mkfifo "$dir/h5pipe"
for out in "$dir/h5pipe" /dev/null; do
  "$sedwave" forward "$scene_data/tiny.toml" --out "$out" > "$dir/log" 2>&1; code=$?
  [ "$code" -ne 0 ] || fail "forward --out $out exited 0"
  grep -q "HDF5 files must be seekable" "$dir/log" || fail "forward --out $out: $(cat "$dir/log")"
  "$sedwave" table "$scene_data/table_resume_grid.toml" --engine long_wavelength --quiet --out "$out" > "$dir/log" 2>&1
  code=$?
  [ "$code" -ne 0 ] && [ "$code" -lt 128 ] || fail "table --out $out: exit $code"
  grep -q "HDF5 files must be seekable" "$dir/log" || fail "table --out $out: $(cat "$dir/log")"
done
"$sedwave" dem "$scene_data/dem_two_grains.data" --steps 10 --kn 1000 --checkpoint "$dir/h5pipe" --every 5 \
  > "$dir/log" 2>&1 && fail "dem --checkpoint FIFO exited 0"
grep -q -- "--checkpoint: cannot write HDF5 to .*h5pipe: it is a FIFO" "$dir/log" || fail "dem --checkpoint: $(cat "$dir/log")"
[ -p "$dir/h5pipe" ] || fail "the FIFO given to an HDF5 output was replaced"
[ -c /dev/null ] || fail "/dev/null is no longer a character device"
ls "$dir" | grep -q corrupt && fail "a FIFO was moved aside as a damaged table"
ls /dev | grep -q 'null\.\|\.tmp-' && fail "something was written beside /dev/null"
echo "ok: FIFO, /dev/null, /dev/full, /dev/stdout and links written safely; HDF5 refused them"
