#!/usr/bin/env bash
# A long `sedwave interface` run says what it will cost before it starts and how far it has got
# while it runs: within SECONDS it must have printed its estimate and at least one progress line
# with the time left. The run is stopped as soon as both are there (it would take hours), or at
# SECONDS, when the check fails.
#   interface_announces.sh SEDWAVE SCENE OUT SECONDS
set -uo pipefail
sedwave="$1"; scene="$2"; out="$3"; seconds="$4"
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
"$sedwave" interface "$scene" --out "$out" >"$log" 2>&1 &
run=$!
announced() {
  grep -Eq '^estimate: about [0-9.e+]+ steps' "$log" &&
    grep -Eq '% of the run\), [0-9]+ steps, .* about [0-9]+ s left' "$log"
}
deadline=$((SECONDS + seconds))
while ! announced && kill -0 "$run" 2>/dev/null && [ "$SECONDS" -lt "$deadline" ]; do sleep 0.2; done
still_running=0
kill -0 "$run" 2>/dev/null && still_running=1
kill "$run" 2>/dev/null
wait "$run" 2>/dev/null
tail -n 20 "$log"
[ "$still_running" = 1 ] || { echo "interface_announces.sh: FAILED: the run ended, expected it still going"; exit 1; }
grep -Eq '^estimate: about [0-9.e+]+ steps' "$log" || { echo "interface_announces.sh: FAILED: no estimate"; exit 1; }
announced || { echo "interface_announces.sh: FAILED: no progress line within $seconds s"; exit 1; }
echo "interface_announces.sh: ok"
