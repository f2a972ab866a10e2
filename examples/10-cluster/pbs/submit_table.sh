#!/usr/bin/env bash
# Submits a member table to PBS Pro: an array of MEMBERS subjobs (-J), then the merge, which waits
# for all of them (depend=afterok on the array). Torque: `qsub -t 0-N` and `-W depend=afterokarray:ID`
# instead. Run it from the folder where the tables should go (or set TABLES).
#
#   GRID=grid.toml PACKING=packing.h5 MEMBERS=5 examples/10-cluster/pbs/submit_table.sh
set -euo pipefail
RECIPES=$(cd "$(dirname "$0")/.." && pwd)
: "${GRID:?set GRID}" "${PACKING:?set PACKING}" "${MEMBERS:?set MEMBERS}"
(( MEMBERS >= 2 )) || { echo "submit_table.sh: a PBS array needs at least 2 members" >&2; exit 2; }
export RECIPES MEMBERS GRID=$(realpath "$GRID") PACKING=$(realpath -m "$PACKING")
export TABLES=$(realpath -m "${TABLES:-$PWD}") NAME=${NAME:-table} SEDWAVE=${SEDWAVE:-$(command -v sedwave)}
array=$(qsub -V -J 0-$((MEMBERS - 1)) "$RECIPES/pbs/table_member.pbs")  # e.g. 1234[].server
merge=$(qsub -V -W depend=afterok:"$array" "$RECIPES/pbs/table_merge.pbs")
echo "members: array $array; merge: $merge (after all members succeed)"
