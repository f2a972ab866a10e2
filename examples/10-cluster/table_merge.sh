#!/usr/bin/env bash
# The body of the merge job that follows a member array (examples/10-cluster): the MEMBERS member
# tables TABLES/NAME.member<K>.h5 into TABLES/NAME.h5 (docs/tables.md, "Ensembles one member at a
# time"). The merge refuses a member table with points missing, naming it: resubmit that array task
# (it resumes) and merge again.
#
# Settings: SEDWAVE, TABLES, NAME as for table_member.sh; MEMBERS the ensemble size.
set -euo pipefail
SEDWAVE=${SEDWAVE:-sedwave}
TABLES=${TABLES:-${SLURM_SUBMIT_DIR:-${PBS_O_WORKDIR:-$PWD}}}
NAME=${NAME:-table}
: "${MEMBERS:?set MEMBERS to the number of ensemble members}"
members=()
for ((k = 0; k < MEMBERS; ++k)); do members+=("$TABLES/$NAME.member$k.h5"); done
"$SEDWAVE" merge "${members[@]}" --out "$TABLES/$NAME.h5"
echo "merged $MEMBERS members: $TABLES/$NAME.h5"
