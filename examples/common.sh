# Shared by every examples/NN-name/run.sh (sourced, not run). It reads the two arguments of an
# example, defines a few checking helpers, and keeps every output under the output directory.
#
#   run.sh [SEDWAVE [OUT]]     or the environment variables SEDWAVE and OUT
#
# SEDWAVE: the sedwave binary (default: build/bin/sedwave of this checkout)
# OUT:     a directory for everything the example writes (default: $TMPDIR/sedwave-examples/NN-name);
#          it is emptied first, and nothing is written anywhere else.
set -euo pipefail

EXAMPLE_DIR=$(cd "$(dirname "${BASH_SOURCE[1]}")" && pwd)   # examples/NN-name
EXAMPLE=$(basename "$EXAMPLE_DIR")
ROOT=$(cd "$EXAMPLE_DIR/../.." && pwd)                     # the repository: data/ lives here
DATA=$ROOT/data

SEDWAVE=${1:-${SEDWAVE:-$ROOT/build/bin/sedwave}}
OUT=${2:-${OUT:-${TMPDIR:-/tmp}/sedwave-examples/$EXAMPLE}}
[ -x "$SEDWAVE" ] || { echo "$EXAMPLE: no sedwave binary at $SEDWAVE (pass it as the first argument)" >&2; exit 2; }
SEDWAVE=$(cd "$(dirname "$SEDWAVE")" && pwd)/$(basename "$SEDWAVE")
case "$(realpath -m "$OUT")/" in "$ROOT"/examples/*|"$ROOT"/data/*|"$ROOT"/docs/*) echo "$EXAMPLE: refusing to write into the source tree: $OUT" >&2; exit 2;; esac
rm -rf "$OUT" && mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
cd "$OUT"

# Open MPI refuses to run as root unless told, and on a small machine two ranks may need to share
# a core; both settings are harmless elsewhere.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
MPIRUN=${MPIRUN:-mpirun}

: > "$OUT/results.txt"
FAILED=0

# small_channel_scene ENGINE: prints the shipped small table's scene with `engine` set (time_domain
# or linear), fitting the layers 2 .. 25 d from the driven wall (max_fit_depth: the DEM's lock-in
# windows reach about that far before echoes could return, and the linear engine would otherwise fit
# the whole column), and one packing for the linear engine ([linear] ensemble = 1).
small_channel_scene() {
  echo "engine = \"$1\""
  cat "$DATA/scenes/table_small_scene.toml"
  printf '\n[drive.measurement]\nmax_fit_depth = 25\n\n[linear]\nensemble = 1\n'
}

# step TEXT: a heading in the example's output.
step() { printf '\n== %s\n' "$*"; }

# run CODE CMD...: run a command, show it, and require its exit status to be CODE
# (0: finished; 3: finished with a flagged result; docs/cli.md, "Exit codes").
run() {
  local want=$1; shift
  printf '$ %s\n' "$*" | sed "s|$SEDWAVE|sedwave|g; s|$DATA|data|g; s|$OUT/||g"
  local rc=0
  "$@" || rc=$?
  if [ "$rc" -ne "$want" ]; then
    echo "FAIL: exit status $rc, expected $want" >&2; exit 1
  fi
}

# json FILE PYTHON-EXPRESSION: one value of a JSON report, e.g. json fit.json "['chi2']".
json() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); v=d$2; print('null' if v is None else v)" "$1"; }

# result KEY VALUE: record a key number; compared with expected.txt at the end.
result() { printf '%-28s %s\n' "$1" "$2" | tee -a "$OUT/results.txt"; }

# check TEXT PYTHON-CONDITION: a property that must hold (evaluated by python3).
check() {
  if python3 -c "import sys; sys.exit(0 if ($2) else 1)"; then
    echo "check: $1: ok"
  else
    echo "check: $1: FAILED ($2)" >&2; FAILED=1
  fi
}

# finish: compare results.txt with expected.txt (KEY EXPECTED TOLERANCE [abs]; relative unless
# "abs"), then exit non-zero if any check failed.
finish() {
  local expected=$EXAMPLE_DIR/expected.txt
  if [ -f "$expected" ]; then
    python3 - "$OUT/results.txt" "$expected" <<'PY' || FAILED=1
import sys
got = {}
for line in open(sys.argv[1]):
    parts = line.split()
    if len(parts) >= 2:
        got[parts[0]] = parts[1]
bad = 0
for line in open(sys.argv[2]):
    line = line.split('#', 1)[0].split()
    if not line:
        continue
    key, want, tol = line[0], line[1], float(line[2])
    absolute = len(line) > 3 and line[3] == 'abs'
    if key not in got:
        print(f"expected: {key}: missing from the results", file=sys.stderr); bad = 1; continue
    try:
        g, w = float(got[key]), float(want)
    except ValueError:
        ok = got[key] == want
        print(f"expected: {key} = {got[key]}, want {want}: {'ok' if ok else 'FAILED'}")
    else:
        limit = tol if absolute else tol * abs(w)
        ok = abs(g - w) <= limit
        print(f"expected: {key} = {g:.6g}, want {w:.6g} +- {limit:.3g}: {'ok' if ok else 'FAILED'}")
    bad |= not ok
sys.exit(bad)
PY
  fi
  if [ "$FAILED" -ne 0 ]; then echo "$EXAMPLE: FAILED" >&2; exit 1; fi
  echo "$EXAMPLE: all checks passed"
}
