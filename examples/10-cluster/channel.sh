#!/usr/bin/env bash
# The body of a job that runs one large channel over several nodes (examples/10-cluster):
# `sedwave dem` on a LAMMPS packing, every rank of the allocation in one engine (slabs along the
# channel, docs/dem.md, "Parallel decomposition"), checkpointing as it goes. The same job
# resubmitted after a kill continues from the last checkpoint (--restart), bit for bit on the same
# number of ranks; on another number of ranks it continues too, to round-off.
#
# Settings: SEDWAVE; LAUNCH the MPI launcher and its options (default: srun under Slurm, mpiexec
# otherwise); DATA the packing (LAMMPS data file); STEPS; RUN the folder for the checkpoint and the
# final state (default: the job's folder); EVERY steps between checkpoints (default 10000); DEM_ARGS
# the engine's other options (contact law, walls, dumps: docs/dem.md).
set -euo pipefail
SEDWAVE=${SEDWAVE:-sedwave}
if [[ -n ${SLURM_JOB_ID:-} ]]; then LAUNCH=${LAUNCH:-srun}; else LAUNCH=${LAUNCH:-mpiexec}; fi
RUN=${RUN:-${SLURM_SUBMIT_DIR:-${PBS_O_WORKDIR:-$PWD}}}
: "${DATA:?set DATA to the packing (LAMMPS data file)}" "${STEPS:?set STEPS}"
mkdir -p "$RUN"
# shellcheck disable=SC2086  # LAUNCH and DEM_ARGS are word lists
$LAUNCH "$SEDWAVE" dem "$DATA" --steps "$STEPS" ${DEM_ARGS:-} \
    --checkpoint "$RUN/checkpoint.h5" --every "${EVERY:-10000}" --restart --final "$RUN/final.data"
