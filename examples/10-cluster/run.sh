#!/usr/bin/env bash
# Example 10: cluster recipes, run here without a scheduler.
#
# slurm/ and pbs/ hold batch scripts for a table computed as a job array of ensemble members
# (`sedwave table --member K`) followed by a dependent `sedwave merge`, and for one large channel
# over several nodes (`sedwave dem` with checkpoints). Their bodies are table_member.sh,
# table_merge.sh and channel.sh; the batch scripts add the scheduler's directives. Here every batch
# script runs as the scheduler would start it, with its array index variable set (Slurm:
# SLURM_ARRAY_TASK_ID, PBS Pro: PBS_ARRAY_INDEX, Torque: PBS_ARRAYID), and the merged table must
# equal, value for value, the table one run over the whole ensemble writes.
#
#   examples/10-cluster/run.sh [SEDWAVE [OUT]]      (MPIRUN=... to choose the launcher)
source "$(dirname "$0")/../common.sh"
RECIPES=$EXAMPLE_DIR
export RECIPES SEDWAVE

step "A two-member linear ensemble on a 2 x 2 grid"
cat > scene.toml <<'TOML'
engine = "linear"
[linear]
ensemble = 2
[geometry]
grains = 300
seed = 7
[contact]
kn = 726.0
[drive]
omega_hat = 1.2
gamma_hat = 0.3
TOML
cat > grid.toml <<'TOML'
scene = "scene.toml"
omega_hat = [1.2, 1.6]
gamma_hat = [0.3, 1.0]
TOML
export GRID=$OUT/grid.toml PACKING=$OUT/packing.h5 MEMBERS=2

step "The whole ensemble in one run (the reference; it prepares and saves both packings)"
run 0 "$SEDWAVE" table grid.toml --engine linear --packing packing.h5 --out one_run.h5 --quiet
"$SEDWAVE" show one_run.h5 --values-only > one_run.csv
python3 - <<'PY' | tee -a "$OUT/results.txt"
import csv
rows = list(csv.DictReader(open('one_run.csv')))
print(f"points_ok  {sum(r['status'] == 'ok' for r in rows)}")
r = next(r for r in rows if float(r['omega_hat']) == 1.2 and float(r['gamma_hat']) == 0.3)
print(f"alpha_hat_at_1.2_0.3  {float(r['alpha_hat']):.6f}")
print(f"c_hat_at_1.2_0.3  {float(r['c_hat']):.6f}")
PY

# members SCHEDULER VARIABLE BATCH-SCRIPT: every array task of BATCH-SCRIPT with VARIABLE = its index,
# then the scheduler's merge script; the tables go to OUT/SCHEDULER.
members() {
  local scheduler=$1 variable=$2 script=$3
  export TABLES=$OUT/$scheduler NAME=table
  for ((k = 0; k < MEMBERS; ++k)); do run 0 env "$variable=$k" bash "$RECIPES/$script"; done
}

step "Slurm: array tasks 0 and 1 (SLURM_ARRAY_TASK_ID), then the merge job"
members slurm SLURM_ARRAY_TASK_ID slurm/table_member.sbatch
run 0 bash "$RECIPES/slurm/table_merge.sbatch"
"$SEDWAVE" show slurm/table.h5 --values-only > slurm.csv
check "Slurm: the merged table equals the one-run table" \
      "open('slurm.csv').read() == open('one_run.csv').read()"

step "PBS Pro: subjobs 0 and 1 (PBS_ARRAY_INDEX), then the merge job"
members pbs PBS_ARRAY_INDEX pbs/table_member.pbs
run 0 bash "$RECIPES/pbs/table_merge.pbs"
"$SEDWAVE" show pbs/table.h5 --values-only > pbs.csv
check "PBS Pro: the merged table equals the one-run table" "open('pbs.csv').read() == open('one_run.csv').read()"

step "Torque: the same PBS script with PBS_ARRAYID"
members torque PBS_ARRAYID pbs/table_member.pbs
run 0 bash "$RECIPES/pbs/table_merge.pbs"
"$SEDWAVE" show torque/table.h5 --values-only > torque.csv
check "Torque: the merged table equals the one-run table" "open('torque.csv').read() == open('one_run.csv').read()"

step "A member task resubmitted after it finished does no work again"
TABLES=$OUT/slurm SLURM_ARRAY_TASK_ID=1 bash "$RECIPES/slurm/table_member.sbatch" > resubmitted.log
"$SEDWAVE" show slurm/table.member1.h5 --values-only > member1_again.csv
check "the member table still holds its 4 points" "open('member1_again.csv').read().count(',ok,') == 4"

step "A task started without an array index is refused"
rc=0; env -u SLURM_ARRAY_TASK_ID -u PBS_ARRAY_INDEX -u PBS_ARRAYID bash "$RECIPES/table_member.sh" 2> noindex.err || rc=$?
cat noindex.err
check "no index: exit status 2 and a message naming the variables" \
      "$rc == 2 and 'SLURM_ARRAY_TASK_ID' in open('noindex.err').read()"

step "One channel on 2 ranks through the Slurm script (srun replaced by MPIRUN), then resubmitted"
# The shipped 1000-grain packing, Hooke contacts, both walls (types 2 and 3) frozen: 400 steps, a checkpoint every 200.
channel=(env DATA="$DATA/tables/thesis_w3_small.packing.data" STEPS=400 EVERY=200 RUN="$OUT/channel"
         LAUNCH="$MPIRUN -np 2" DEM_ARGS="--kn 726 --restitution 0.9 --frozen 2 --frozen 3 --quiet")
run 0 "${channel[@]}" bash "$RECIPES/slurm/channel.sbatch"
cp channel/final.data first_final.data
# The resubmitted job (here through the PBS script) finds the checkpoint of step 400: nothing is left.
run 0 "${channel[@]}" bash "$RECIPES/pbs/channel.pbs"
check "the channel ran and checkpointed" \
      "__import__('os').path.exists('channel/checkpoint.h5') and __import__('os').path.getsize('first_final.data') > 0"
check "the resubmitted job ends in the same state, byte for byte" \
      "__import__('filecmp').cmp('first_final.data', 'channel/final.data', shallow=False)"
finish
