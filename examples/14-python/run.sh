#!/usr/bin/env bash
# examples/14-python: the Python module on the shipped field data (README.md). The script is what a
# notebook user would copy; this wrapper runs it with the interpreter the module is built for and
# checks its numbers.
source "$(dirname "$0")/../common.sh"
PYTHON=${PYTHON:-/usr/bin/python3}

step "The study from Python (example.py)"
"$PYTHON" "$EXAMPLE_DIR/example.py" "$OUT"
cat "$OUT/results.txt"
r() { awk -v k="$1" '$1 == k { print $2 }' "$OUT/results.txt"; }
check "biot-stoll ranked first" "'$(r best_model)' == 'biot-stoll'"
check "the Python model ranked last by far" "$(r ln_Z_constant-q-py) < $(r ln_Z_edfm) - 100"
check "compare.json written" "__import__('os').path.exists('compare/compare.json')"
if "$PYTHON" -c "import matplotlib" 2>/dev/null; then
  check "the figure drawn" "__import__('os').path.getsize('bands.png') > 10000"
fi
finish
