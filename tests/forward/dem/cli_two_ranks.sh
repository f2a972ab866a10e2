#!/usr/bin/env bash
# `sedwave dem` under mpirun -np 2: a run with checkpoint, LAMMPS dump, H5MD trajectory and final
# state, then a --restart to a later step (the files are cut back to the checkpoint and appended).
# Checks the multi-rank paths of the command (reading shares, rank-by-rank writers, restore), and
# that the restarted run ends byte for byte as an uninterrupted one on the same 2 ranks (each rank
# reads back the grains it wrote), and that a malformed data file is refused naming its line.
#
# Usage: cli_two_ranks.sh MPIEXEC SEDWAVE DATA_FILE WORK_DIR
set -euo pipefail
mpiexec=$1
sedwave=$2
data=$3
work=$4
rm -rf "$work"
mkdir -p "$work"
cd "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
scene=(dem "$data" --kn 1000 --restitution 0.7 --friction 0.5 --gravity 0,0,-1 --frozen 2
       --checkpoint run.h5 --every 300 --dump run.dump --dump-every 100 --h5md run_traj.h5 --h5md-every 100
       --final final.data --progress 1000)
"$mpiexec" -np 2 --oversubscribe "$sedwave" "${scene[@]}" --steps 600 > first.log
"$mpiexec" -np 2 --oversubscribe "$sedwave" "${scene[@]}" --steps 1000 --restart > second.log
cat first.log second.log
grep -q "2 rank(s)" first.log || { echo "FAIL: not on 2 ranks" >&2; exit 1; }
grep -q "restarting from run.h5 at step 600" second.log || { echo "FAIL: no restart at step 600" >&2; exit 1; }
grep -q "finished at step 1000" second.log || { echo "FAIL: did not reach step 1000" >&2; exit 1; }
frames=$(grep -c "ITEM: TIMESTEP" run.dump)
[[ $frames -eq 11 ]] || { echo "FAIL: the dump has $frames frames, expected 11 (steps 0..1000)" >&2; exit 1; }
atoms=$(awk 'NR == 3 {print $1}' final.data)
[[ $atoms -eq 128 ]] || { echo "FAIL: final state has $atoms grains" >&2; exit 1; }
straight=(dem "$data" --kn 1000 --restitution 0.7 --friction 0.5 --gravity 0,0,-1 --frozen 2
          --checkpoint straight.h5 --every 300 --dump straight.dump --dump-every 100 --final straight.data --quiet)
"$mpiexec" -np 2 --oversubscribe "$sedwave" "${straight[@]}" --steps 1000
cmp final.data straight.data || { echo "FAIL: the restarted run ends elsewhere than the uninterrupted one" >&2; exit 1; }
cmp run.dump straight.dump || { echo "FAIL: the restarted dump differs from the uninterrupted one" >&2; exit 1; }
# Each rank parses its share of the file's bytes: a malformed line in the second rank's share (the
# last Velocities line) is named with its line number in the whole file, and the run fails.
lines=$(wc -l < "$data")
awk -v last="$lines" 'NR == last { $2 = "fast" } { print }' "$data" > bad.data
if "$mpiexec" -np 2 --oversubscribe "$sedwave" dem bad.data --kn 1000 --restitution 0.7 --steps 10 --quiet \
    > bad.log 2>&1; then
  echo "FAIL: a malformed data file was accepted on 2 ranks" >&2; exit 1
fi
grep -q "bad.data:$lines: bad velocity 'fast'" bad.log || { cat bad.log; echo "FAIL: the error does not name bad.data:$lines" >&2; exit 1; }
echo "PASS: 2 ranks, restarted at step 600, 11 dump frames, 128 grains in the final state, identical to an uninterrupted run; a malformed line named at bad.data:$lines"
