#!/usr/bin/env bash
# Compiler launcher for two builds that run side by side (scripts/test.sh): runs the command once
# one of $SEDWAVE_CPU_SLOTS slots is free, so that the two builds together run no more compilers
# than there are cores. Each build alone would start one per core; two of them side by side would
# start two per core, and compilers time-sharing a core cost 12-20 % more CPU for the same work
# (docs/performance.md, "The test command"). A slot is a lock file in $SEDWAVE_CPU_SLOT_DIR, held
# by the command (it inherits the open descriptor) until it exits. Without $SEDWAVE_CPU_SLOT_DIR
# the command simply runs.
#
#   scripts/cpu_slot.sh COMMAND [ARGS...]
set -uo pipefail
if [ -z "${SEDWAVE_CPU_SLOT_DIR:-}" ]; then exec "$@"; fi
slots="${SEDWAVE_CPU_SLOTS:-2}"
while :; do
  for ((i = 0; i < slots; i++)); do
    exec 9>>"$SEDWAVE_CPU_SLOT_DIR/slot$i"
    if flock -n 9; then exec "$@"; fi
    exec 9>&-
  done
  sleep 0.05
done
