#!/usr/bin/env bash
# How fast one planar Hertz + Coulomb-tanh contact can be evaluated (docs/performance.md, "Per
# contact"): through the DEM engine's parts one at a time, in plane form one at a time, and in plane
# form over arrays in SIMD lanes, and by the interface's own kernel (its AVX2 clone chosen at run time),
# with the baseline instruction set and with AVX2 + FMA. Compiled here
# by the system's C++ compiler (not part of the CMake build); prints a table per instruction set.
#   bench/interface/contact_lanes.sh
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
# The lanes need sqrt without errno and selects without trapping divisions to vectorise.
FLAGS=(-std=c++20 -O3 -DNDEBUG -fopenmp-simd -fno-math-errno -fno-trapping-math
       -I"$ROOT/forward/include" -I"$ROOT/io/include")
SOURCE=("$ROOT/bench/interface/contact_lanes.cpp" "$ROOT/forward/src/interface/planar_contacts.cpp")
"${CXX:-c++}" "${FLAGS[@]}" "${SOURCE[@]}" -o "$OUT/baseline"
echo "the compiler's default instruction set (x86-64: SSE2, 2 lanes)"
"$OUT/baseline"
if grep -qw avx2 /proc/cpuinfo 2>/dev/null && grep -qw fma /proc/cpuinfo; then
  "${CXX:-c++}" "${FLAGS[@]}" -mavx2 -mfma "${SOURCE[@]}" -o "$OUT/avx2"
  echo "AVX2 + FMA (4 lanes)"
  "$OUT/avx2"
fi
