#!/usr/bin/env bash
# A long `sedwave interface` run says what it will cost before it starts and how far it has got
# while it runs: within SECONDS it must have printed its estimate and at least one progress line
# with the time left. The run is then stopped (it would take hours).
#   interface_announces.sh SEDWAVE SCENE OUT SECONDS
set -uo pipefail
sedwave="$1"; scene="$2"; out="$3"; seconds="$4"
output="$(timeout "$seconds" "$sedwave" interface "$scene" --out "$out" 2>&1)"
code=$?
printf '%s\n' "$output" | tail -n 20
[ "$code" -eq 124 ] || { echo "interface_announces.sh: FAILED: exit $code, expected the run still going (124)"; exit 1; }
grep -Eq '^estimate: about [0-9.e+]+ steps' <<< "$output" || { echo "interface_announces.sh: FAILED: no estimate"; exit 1; }
grep -Eq '% of the run\), [0-9]+ steps, .* about [0-9]+ s left' <<< "$output" ||
  { echo "interface_announces.sh: FAILED: no progress line within $seconds s"; exit 1; }
echo "interface_announces.sh: ok"
