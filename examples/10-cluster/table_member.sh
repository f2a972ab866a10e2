#!/usr/bin/env bash
# The body of one array task of a member table (examples/10-cluster): ensemble member K of a
# linear-engine table, K taken from the scheduler's array index. Shared by the Slurm and PBS
# scripts beside it (they add only their directives); ctest runs it with each index set.
#
#   Slurm: SLURM_ARRAY_TASK_ID   PBS Pro: PBS_ARRAY_INDEX   Torque: PBS_ARRAYID
#
# Settings (environment; the submit scripts pass them on):
#   SEDWAVE  the sedwave binary (default: sedwave on PATH)
#   GRID     the grid file (docs/tables.md, "The grid file")
#   PACKING  the ensemble's packing file P.h5: member K reads (or prepares and saves) P.memberK.h5
#            (member 0: P.h5 itself)
#   TABLES   the folder for the member tables TABLE.member<K>.h5 (default: the job's folder)
#   NAME     the tables' base name (default: table)
# A task killed by the scheduler (time limit, preemption) resumes where it stopped when it runs
# again: finished points are journalled (docs/tables.md, "Writing point by point").
set -euo pipefail
K=${SLURM_ARRAY_TASK_ID:-${PBS_ARRAY_INDEX:-${PBS_ARRAYID:-}}}
if [[ -z $K ]]; then
  echo "table_member.sh: no array index (SLURM_ARRAY_TASK_ID, PBS_ARRAY_INDEX or PBS_ARRAYID)" >&2
  exit 2
fi
SEDWAVE=${SEDWAVE:-sedwave}
TABLES=${TABLES:-${SLURM_SUBMIT_DIR:-${PBS_O_WORKDIR:-$PWD}}}
NAME=${NAME:-table}
: "${GRID:?set GRID to the grid file}" "${PACKING:?set PACKING to the ensemble packing file}"
mkdir -p "$TABLES"
# One process per member: the linear engine holds the member's packing and solves point by point.
# An exit status of 3 (some point flagged) still leaves a complete member table for the merge.
rc=0
"$SEDWAVE" table "$GRID" --engine linear --member "$K" --packing "$PACKING" \
    --out "$TABLES/$NAME.member$K.h5" --quiet || rc=$?
if [[ $rc -ne 0 && $rc -ne 3 ]]; then exit "$rc"; fi
echo "member $K: $TABLES/$NAME.member$K.h5"
