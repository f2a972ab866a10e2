#!/usr/bin/env bash
# A farm run killed mid-table (rank 0 exits abruptly after K points; mpirun takes the others down)
# and restarted with the same command skips the finished points and ends with the same table as an
# uninterrupted run. Checked on 1 and 2 ranks.
# usage: farm_resume.sh MPIEXEC FARM_DRIVER DATA_DIR WORK_DIR
set -euo pipefail
mpiexec=$1 driver=$2 data=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
run() { local np=$1; shift; "$mpiexec" -np "$np" --oversubscribe "$driver" "$@"; }
grid=$data/farm_grid.toml

run 1 "$grid" "$work/reference.h5"
for np in 1 2; do
  table=$work/killed_np$np.h5
  if run "$np" "$grid" "$table" --point-ms 20 --die-after 5 > "$work/first_np$np.log" 2>&1; then
    echo "farm_resume: the run that should have died finished" >&2; exit 1
  fi
  finished=$(grep -vc "^#" "$table.journal")
  echo "np $np: killed with $finished points in the journal"
  [ "$finished" -ge 5 ] || { echo "farm_resume: expected >= 5 finished points, got $finished" >&2; exit 1; }
  [ "$finished" -lt 21 ] || { echo "farm_resume: the table was already complete" >&2; exit 1; }
  run "$np" "$grid" "$table" --point-ms 20 | tee "$work/second_np$np.log"
  grep -q "already_finished $finished computed $((21 - finished)) " "$work/second_np$np.log" ||
    { echo "farm_resume: the restart did not skip exactly the $finished finished points" >&2; exit 1; }
  "$driver" --compare "$work/reference.h5" "$table"
done
echo "farm_resume: restarted runs skip finished points and equal the uninterrupted table"
