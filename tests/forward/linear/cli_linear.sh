#!/usr/bin/env bash
# The linear engine end to end from the command line: `sedwave forward` on a linear scene (an
# ensemble of two packings, saved), then `sedwave table --engine linear` on two MPI ranks reusing
# those packings, then the same table command again, which must find every point finished; the
# same ensemble one member per run (--member K) and merged (sedwave merge), which must give the
# same table value for value; and `--engine long_wavelength` on a pulse scene with the same packing.
# usage: cli_linear.sh MPIEXEC SEDWAVE DATA_DIR WORK_DIR
set -euo pipefail
mpiexec=$1 sedwave=$2 data=$3 work=$4
rm -rf "$work" && mkdir -p "$work"

"$sedwave" forward "$data/tiny_linear.toml" --out "$work/run.h5" --packing-out "$work/packing.h5" | tee "$work/forward.log"
grep -q "linear engine, 2 packing(s)" "$work/forward.log"
grep -Eq "^alpha_hat [0-9.e-]+ \+- [0-9.e-]+ +c_hat [0-9.e-]+" "$work/forward.log"
test -f "$work/packing.member1.h5"

table() { "$mpiexec" -np 2 --oversubscribe "$sedwave" table "$data/tiny_grid.toml" --engine linear \
            --out "$work/table.h5" --packing "$work/packing.h5"; }
table | tee "$work/table.log"
grep -q "4 points, 0 already finished, 4 computed" "$work/table.log"
table | tee "$work/resume.log"
grep -q "4 points, 4 already finished, 0 computed" "$work/resume.log"

# The same ensemble one member at a time (sedwave table --member K), merged: the same table.
for k in 0 1; do
  "$sedwave" table "$data/tiny_grid.toml" --engine linear --member $k --out "$work/member$k.h5" \
      --packing "$work/packing.h5" --quiet
done
"$sedwave" merge "$work/member0.h5" "$work/member1.h5" --out "$work/merged.h5"
"$sedwave" show "$work/table.h5" --values-only > "$work/table.csv"
"$sedwave" show "$work/merged.h5" --values-only > "$work/merged.csv"
cmp "$work/table.csv" "$work/merged.csv"
grep -q "^1.2,0.3,ok," "$work/merged.csv"
if "$sedwave" merge "$work/member0.h5" "$work/member0.h5" --out "$work/twice.h5" 2> "$work/twice.err"; then
  echo "merging a member with itself must fail"; exit 1
fi
grep -q "is member 0 again" "$work/twice.err"
# A member table named like a member's packing file would overwrite it: refused before anything runs.
if "$sedwave" table "$data/tiny_grid.toml" --engine linear --member 1 --packing "$work/packing.h5" \
    --out "$work/packing.member1.h5" 2> "$work/clash.err"; then
  echo "a table over a packing file must be refused"; exit 1
fi
grep -q "would overwrite the input .*packing.member1.h5" "$work/clash.err"
test -f "$work/packing.member1.h5"

# The long-wavelength engine on a pulse scene: it ignores the drive, so the scene is accepted.
"$sedwave" table "$data/tiny_pulse_grid.toml" --engine long_wavelength --out "$work/limit.h5" \
    --packing "$work/packing.h5" --quiet | tee "$work/limit.log"
grep -q "4 points, 0 already finished, 4 computed (4 ok" "$work/limit.log"
echo "cli_linear: forward and table with the linear engine work, and the table resumes"
