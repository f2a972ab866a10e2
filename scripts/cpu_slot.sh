#!/usr/bin/env bash
# Compiler launcher for two builds that run side by side (scripts/test.sh): runs the command once
# one of $SEDWAVE_CPU_SLOTS slots is free, so that the builds together run no more compilers than
# there are cores. Each build alone would start one per core; two side by side would start two per
# core, and compilers time-sharing a core cost 12-21 % more CPU for the same work
# (docs/performance.md, "The test command"). A slot is a lock file in $SEDWAVE_CPU_SLOT_DIR, held
# by the command (it inherits the open descriptor) until it exits.
#
# SEDWAVE_CPU_SLOT_PRIORITY=low (the sanitizer build): take a slot only when no other build is
# waiting for it (low-priority launchers look once a second, the others wait on the lock and get it
# as soon as it is released). Without $SEDWAVE_CPU_SLOT_DIR the command simply runs.
#
#   scripts/cpu_slot.sh COMMAND [ARGS...]
set -uo pipefail
dir="${SEDWAVE_CPU_SLOT_DIR:-}"
if [ -z "$dir" ]; then exec "$@"; fi
slots="${SEDWAVE_CPU_SLOTS:-2}"
low=0
[ "${SEDWAVE_CPU_SLOT_PRIORITY:-}" = low ] && low=1

try_every_slot() {
  local i
  for ((i = 0; i < slots; i++)); do
    exec 9>>"$dir/slot$i"
    if flock -n 9; then exec "$@"; fi
    exec 9>&-
  done
}

while :; do
  try_every_slot "$@"
  if [ "$low" = 1 ]; then
    sleep 1
    continue
  fi
  # All taken: wait on one of them (released ones are looked at again after a second).
  exec 9>>"$dir/slot$(($$ % slots))"
  if flock -w 1 9; then exec "$@"; fi
  exec 9>&-
done
