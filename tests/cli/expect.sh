#!/usr/bin/env bash
# Runs one command-line case and checks what a user would see:
#   expect.sh EXIT REGEX [--in DIR] -- COMMAND ARGS...
# passes when COMMAND exits with exactly EXIT within 120 s (a hang fails) and its combined
# stdout+stderr matches the extended regular expression REGEX (grep -E, case-insensitive).
# --in DIR runs the command in a fresh copy of DIR (so cases that write files start clean).
set -uo pipefail
want_exit="$1"; regex="$2"; shift 2
workdir=""
if [ "${1:-}" = "--in" ]; then workdir="$2"; shift 2; fi
[ "${1:-}" = "--" ] && shift
if [ -n "$workdir" ]; then
  rm -rf "$workdir.run" && cp -r "$workdir" "$workdir.run" && cd "$workdir.run" || exit 99
fi
output="$(timeout 120 "$@" 2>&1)"
code=$?
printf '%s\n' "$output" | tail -n 30
if [ "$code" -eq 124 ]; then echo "expect.sh: FAILED: the command hung (killed after 120 s)"; exit 1; fi
if [ "$code" -ne "$want_exit" ]; then echo "expect.sh: FAILED: exit code $code, expected $want_exit"; exit 1; fi
# A here-string, not a pipe: grep -q stops reading at the first match, and under pipefail the writer
# of a pipe killed by SIGPIPE would turn a match into a failure.
if ! grep -Eiq -- "$regex" <<< "$output"; then
  echo "expect.sh: FAILED: output does not match /$regex/"; exit 1
fi
echo "expect.sh: ok (exit $code, message matches)"
