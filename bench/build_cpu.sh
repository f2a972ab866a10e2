#!/usr/bin/env bash
# CPU seconds (user + system) of a build from nothing, step by step and summed by part: the
# libraries, the `sedwave` command, the tests and the benchmarks, compiling and linking apart.
# Each compiler and linker call runs under /usr/bin/time (a launcher), so the figures do not depend
# on other work sharing the machine, as wall times would. No compiler cache (CCACHE_DISABLE=1).
# Usage (repository root): bench/build_cpu.sh BUILD_DIR [cmake options ...]
# (TARGETS="a b" builds only those targets, with what they need.)
#   bench/build_cpu.sh /tmp/cpu-release -DCMAKE_BUILD_TYPE=Release -DSEDWAVE_WERROR=ON
#   bench/build_cpu.sh /tmp/cpu-unity-off -DCMAKE_BUILD_TYPE=Release -DSEDWAVE_UNITY_BUILD=OFF
# Prints the 15 most expensive steps, then the sums; the raw log stays in BUILD_DIR/cpu_steps.log
# (user, system, wall seconds, peak memory in kB, output file).
set -euo pipefail
BUILD="${1:?usage: bench/build_cpu.sh BUILD_DIR [cmake options ...]}"
shift
[ -e "$BUILD" ] && { echo "build_cpu.sh: $BUILD exists; give a new folder (the build must start from nothing)" >&2; exit 1; }
mkdir -p "$BUILD"
BUILD="$(cd "$BUILD" && pwd)"
LOG="$BUILD/cpu_steps.log"
cat >"$BUILD/timed" <<LAUNCHER
#!/usr/bin/env bash
out=""; prev=""
for a in "\$@"; do [ "\$prev" = "-o" ] && out="\$a"; prev="\$a"; done
exec /usr/bin/time -f "%U %S %e %M \$out" -a -o "$LOG" "\$@"
LAUNCHER
chmod +x "$BUILD/timed"
export CCACHE_DISABLE=1
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_CXX_COMPILER_LAUNCHER="$BUILD/timed" \
  -DCMAKE_CXX_LINKER_LAUNCHER="$BUILD/timed" "$@" >/dev/null
# shellcheck disable=SC2086 # TARGETS is a list of names
cmake --build "$BUILD" -j "${JOBS:-$(nproc)}" ${TARGETS:+--target $TARGETS} >"$BUILD/build.out"

echo "most expensive steps (CPU s = user + system):"
awk 'NF == 5 { printf "%8.1f  %s\n", $1 + $2, $5 }' "$LOG" | sort -rn | head -15
echo
echo "by part:"
awk 'NF == 5 {
  out = $5; part = "libraries"
  if (out ~ /(^|\/)bench/ || out ~ /^bin\/(bench|dem_bench)/) part = "benchmarks"
  else if (out ~ /^tests\//) part = "tests"
  else if (out ~ /^apps\// || out == "bin/sedwave") part = "command"
  step = (out ~ /\.o$/) ? "compile" : "link"
  n[part " " step]++; cpu[part " " step] += $1 + $2; total += $1 + $2
} END {
  for (k in cpu) printf "  %-22s %4d steps %8.1f s\n", k, n[k], cpu[k]
  printf "  %-22s %4s       %8.1f s\n", "total", "", total
}' "$LOG" | sort
