#!/usr/bin/env bash
# Submits a member table to Slurm: an array of MEMBERS tasks, then the merge, which waits for all of
# them (afterok). Run it from the folder where the tables should go (or set TABLES).
#
#   GRID=grid.toml PACKING=packing.h5 MEMBERS=5 examples/10-cluster/slurm/submit_table.sh
set -euo pipefail
RECIPES=$(cd "$(dirname "$0")/.." && pwd)
: "${GRID:?set GRID}" "${PACKING:?set PACKING}" "${MEMBERS:?set MEMBERS}"
export RECIPES MEMBERS GRID=$(realpath "$GRID") PACKING=$(realpath -m "$PACKING")
export TABLES=$(realpath -m "${TABLES:-$PWD}") NAME=${NAME:-table} SEDWAVE=${SEDWAVE:-$(command -v sedwave)}
array=$(sbatch --parsable --export=ALL --array=0-$((MEMBERS - 1)) "$RECIPES/slurm/table_member.sbatch")
array=${array%%;*}  # --parsable prints "jobid[;cluster]"
merge=$(sbatch --parsable --export=ALL --dependency=afterok:"$array" "$RECIPES/slurm/table_merge.sbatch")
echo "members: job array $array; merge: job ${merge%%;*} (after all members succeed)"
