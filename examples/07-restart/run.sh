#!/usr/bin/env bash
# Example 07: stop a run, resume it.
#
# Long runs get killed: a time limit, a reboot, a full disk. Two kinds of sedwave run survive it.
#  1. `sedwave dem` writes checkpoints; `--restart` continues from the last one, and the result is
#     bit for bit the one an uninterrupted run gives.
#  2. `sedwave table` journals every finished point; the same command again skips them and computes
#     only the rest.
# Both runs here are killed with SIGKILL (no chance to clean up) and then resumed.
#
#   examples/07-restart/run.sh [SEDWAVE [OUT]]
source "$(dirname "$0")/../common.sh"

# wait_for FILE PID: wait until FILE holds a line not starting with '#', or PID has ended.
wait_for() {
  while kill -0 "$2" 2>/dev/null && ! grep -qv '^#' "$1" 2>/dev/null; do sleep 0.05; done
}

# --- 1. The bare DEM engine ------------------------------------------------------------------------
# The shipped 1000-grain packing as a LAMMPS data file: type 1 flow grains, types 2 and 3 the rough
# walls. Wall 3 is frozen, wall 2 oscillates along z (amplitude 0.01, period 15), Hooke contacts
# kn = 726 with restitution 0.9: 20 000 steps.
DEM=("$SEDWAVE" dem "$DATA/tables/thesis_w3_small.packing.data" --steps 20000 --kn 726
     --restitution 0.9 --frozen 3 --wiggle 2:z:0.01:15 --quiet)

step "DEM: an uninterrupted run, with checkpoints every 1000 steps"
# Writing a checkpoint forces a neighbour-list rebuild at the next step, as loading one does; that
# is what makes a restart bit-identical. So the reference run writes checkpoints at the same steps
# (a run without any differs from it in the last digits: the pairs are summed in another order).
run 0 "${DEM[@]}" --checkpoint uninterrupted.h5 --every 1000 --final uninterrupted.data

step "DEM: the same run again, killed after its first checkpoint"
# --checkpoint is replaced atomically, so a kill never leaves half a checkpoint.
"${DEM[@]}" --checkpoint checkpoint.h5 --every 1000 --restart --final resumed.data &
pid=$!
while kill -0 $pid 2>/dev/null && [ ! -e checkpoint.h5 ]; do sleep 0.02; done
kill -KILL $pid 2>/dev/null || true
rc=0; wait $pid || rc=$?
echo "killed: exit status $rc"
check "the DEM run was killed before it finished" "$rc == 137 and not __import__('os').path.exists('resumed.data')"

step "DEM: the same command again continues from the checkpoint"
run 0 "${DEM[@]}" --checkpoint checkpoint.h5 --every 1000 --restart --final resumed.data
# --final writes 17 significant digits, so equal files mean bit-identical states.
check "the resumed final state equals the uninterrupted one, byte for byte" \
      "__import__('filecmp').cmp('uninterrupted.data', 'resumed.data', shallow=False)"

# --- 2. A table ------------------------------------------------------------------------------------
cat > grid.toml <<TOML
scene = "$DATA/scenes/table_small_scene.toml"
omega_hat = [0.4, 0.8]
gamma_hat = [0.3]
TOML
TABLE=("$SEDWAVE" table grid.toml --packing "$DATA/tables/thesis_w3_small.packing.h5" --out table.h5)

step "Table: two points on one rank, killed once the first is journalled"
"${TABLE[@]}" &
pid=$!
wait_for table.h5.journal $pid
kill -KILL $pid 2>/dev/null || true
rc=0; wait $pid || rc=$?
echo "killed: exit status $rc"
grep -v '^#' table.h5.journal | cut -d' ' -f3-7
check "the table run was killed with one point finished" \
      "$rc == 137 and sum(1 for l in open('table.h5.journal') if not l.startswith('#')) == 1"

step "Table: the same command again"
run 0 "${TABLE[@]}" | tee resume.log
check "the resumed run skipped the finished point" "'1 already finished, 1 computed' in open('resume.log').read()"
# The completed table equals the shipped one (same packing; made uninterrupted) at both points.
"$SEDWAVE" show --values-only table.h5 | tee resumed.csv
"$SEDWAVE" show --values-only "$DATA/tables/thesis_w3_small.h5" > shipped.csv
python3 - <<'PY' | tee -a "$OUT/results.txt"
import csv
key = lambda r: (round(float(r['omega_hat']), 9), round(float(r['gamma_hat']), 9))
shipped = {key(r): r for r in csv.DictReader(open('shipped.csv'))}
for r in csv.DictReader(open('resumed.csv')):
    s = shipped[key(r)]
    for q in ('alpha_hat', 'c_hat'):
        print(f"{q}_at_{key(r)[0]:g}  {float(r[q]):.6f}")
        print(f"distance_{q}_at_{key(r)[0]:g}_in_sigma  {abs(float(r[q]) - float(s[q])) / float(s['sigma_' + q]):.4f}")
PY
check "every resumed value within sigma/10 of the uninterrupted table" \
      "all(float(l.split()[1]) < 0.1 for l in open('results.txt') if l.startswith('distance_'))"
finish
