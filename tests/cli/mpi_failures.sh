#!/usr/bin/env bash
# How the MPI commands fail on several ranks (docs/cli.md, "Exit codes"): a mistake that every rank
# meets alike (a scene's unknown key, an output that would overwrite an input, an unreadable
# packing found during the run, a misspelt option) is told in one line and every rank exits with its status; a failure
# on one rank alone ends the whole job, naming the rank, instead of leaving the others waiting.
#
# Usage: mpi_failures.sh MPIEXEC SEDWAVE PROBE SCENE WORK_DIR
set -uo pipefail
mpiexec=$1 sedwave=$2 probe=$3 scene=$4 work=$5
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
failures=0
# expect NAME STATUS LINES REGEX -- COMMAND...: COMMAND on 2 ranks exits with STATUS within 60 s,
# and its output holds LINES lines matching REGEX and no HDF5 error stack.
expect() {
  local name=$1 status=$2 lines=$3 regex=$4
  shift 5
  timeout 60 "$mpiexec" -np 2 --oversubscribe "$@" > "$name.log" 2>&1
  local code=$?
  local seen
  seen=$(grep -cE -- "$regex" "$name.log")
  if [[ $code -ne $status || $seen -ne $lines ]] || grep -q "HDF5-DIAG" "$name.log"; then
    cat "$name.log"
    echo "FAIL: $name: exit $code (expected $status), $seen line(s) matching /$regex/ (expected $lines)"
    failures=$((failures + 1))
  else
    echo "ok: $name: exit $code, $seen line(s) matching /$regex/"
  fi
}
sed 's/^law = "hooke"/law = "hooke"\nkn_typo = 1.0/' "$scene" > typo.toml
expect unknown_key 1 1 "^sedwave: error: typo.toml:[0-9]+: key 'contact.kn_typo'" -- "$sedwave" forward typo.toml
cp "$scene" scene.toml
expect output_is_input 2 1 "^sedwave: usage error: .*would overwrite the input" -- \
  "$sedwave" forward scene.toml --out scene.toml
printf 'not an HDF5 file\n' > broken.packing.h5
expect unreadable_packing 1 1 "^sedwave: error: HDF5: cannot open broken.packing.h5 \\(file signature not found\\)" -- \
  "$sedwave" forward scene.toml --packing broken.packing.h5 --quiet
expect misspelt_option 2 1 "^The following arguments? (was|were) not expected:.*--omega-haat" -- \
  "$sedwave" forward scene.toml --omega-haat 0.5
expect one_rank_fails 1 1 "^sedwave: error on rank 1: only rank 1 fails" -- "$probe"
[[ $failures -eq 0 ]] || exit 1
echo "PASS: agreed failures told once with their status; a one-rank failure ends the job"
