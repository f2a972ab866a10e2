#!/usr/bin/env bash
# A `sedwave dem` run killed with SIGKILL after its first checkpoint and continued with --restart
# must end bit for bit where an uninterrupted run ends (one rank): the final-state files (17
# significant digits) and the dumps are compared with cmp.
#
# Usage: restart_sigkill.sh SEDWAVE DATA_FILE WORK_DIR
# The scene (128 grains, friction with contact history, wiggling floor, gravity) runs 20000 steps,
# about a second; the first checkpoint comes after 5 % of it, so the kill lands mid-run even when
# this script is slowed down by a loaded machine.
set -euo pipefail
sedwave=$1
data=$2
work=$3
rm -rf "$work"
mkdir -p "$work"
cd "$work"

scene=(dem "$data" --steps 20000 --boundary ppf --kn 1000 --restitution 0.7 --friction 0.5
       --gravity 0,0,-1 --wiggle 2:z:0.001:0.37 --every 1000 --dump-every 100 --progress 1000)

"$sedwave" "${scene[@]}" --checkpoint straight.h5 --dump straight.dump --final straight.data > straight.log

"$sedwave" "${scene[@]}" --checkpoint killed.h5 --dump killed.dump --final killed.data --restart > killed.log &
pid=$!
for _ in $(seq 6000); do  # up to 60 s
  [[ -f killed.h5 ]] && break
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.01
done
kill -KILL "$pid" 2>/dev/null || true
status=0
{ wait "$pid"; } 2>/dev/null || status=$?
if [[ $status -ne 137 ]]; then
  echo "FAIL: the run to be killed ended with status $status before SIGKILL reached it" >&2
  exit 1
fi
[[ ! -f killed.data ]] || { echo "FAIL: the killed run wrote its final state" >&2; exit 1; }
echo "killed with $(grep -c TIMESTEP killed.dump) dump frames written (the restart cuts those past the checkpoint)"

"$sedwave" "${scene[@]}" --checkpoint killed.h5 --dump killed.dump --final killed.data --restart > restarted.log
cat restarted.log
grep -Eq "restarting from killed.h5 at step [1-9][0-9]*" restarted.log ||
  { echo "FAIL: the second run did not restart from the checkpoint" >&2; exit 1; }
cmp straight.data killed.data || { echo "FAIL: final states differ" >&2; exit 1; }
cmp straight.dump killed.dump || { echo "FAIL: dumps differ" >&2; exit 1; }
echo "PASS: killed, continued from the checkpoint $(grep -Eo "at step [0-9]+" restarted.log | head -1): final state and dump bit-identical"
