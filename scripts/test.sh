#!/usr/bin/env bash
# Set up a fresh Debian machine (as root), build with warnings as errors, then run every test with
# ctest beside a second, sanitized build (AddressSanitizer + UBSan) that runs the unit tests and
# every command-line case; the last lines give both verdicts.
# SEDWAVE_SANITIZE_TESTS=0 skips the sanitizer pass (a second build, with Clang, of those targets).
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
# Clang, its sanitizer runtimes and OpenMP build the sanitizer pass; matplotlib draws example 14's figure.
sedwave_install_packages clang libclang-rt-dev libomp-dev python3-matplotlib
# Open MPI refuses to run as root and to oversubscribe 2 cores unless told it may.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
# Tests run several programs per core. An OpenMP thread waiting at a barrier then sleeps instead of
# spinning on a core that another test needs (docs/performance.md, "The test command").
export OMP_WAIT_POLICY=PASSIVE

# The sanitizer pass: under AddressSanitizer + UBSan, the theories, the sediment models, the inversion, tables and
# HDF5 files, the DEM engine, the linear-response engine, and every command-line case (tests/cli: bad input of every
# kind, restarts, outputs) through a sanitized `sedwave`. Open MPI's own allocations are not ours to fix: no leak check.
SAN_DIR="${BUILD_DIR}-sanitize"
# The unit-test programs the pass builds and runs (paths in the build tree, longest first). The
# Release build leaves them out, all but test_channel_table, which docs/tables.md runs from it.
SANITIZED_PROGRAMS=(tests/test_linear tests/forward/dem/test_dem tests/test_inversion tests/test_sediment
                    tests/test_channel_table tests/test_theory tests/test_io)
sanitizer_pass() {
  local targets=("${SANITIZED_PROGRAMS[@]##*/}" sedwave)
  # Its compilations give way to the Release build's (scripts/cpu_slot.sh): ctest starts sooner.
  export SEDWAVE_CPU_SLOT_PRIORITY=low
  # Clang, the sanitizers' own compiler: it compiles this build in 70 % of GCC's CPU time, and 56 %
  # with the third-party headers left uninstrumented (cmake/sanitizer_ignorelist.txt); a second
  # compiler's warnings are errors too. -O1 with line tables only (-g1): the sanitizers' reports keep
  # function, file and line (docs/performance.md, "The test command").
  # A folder configured with another compiler starts afresh: CMake would drop the options below
  # when it changes the compiler of an existing cache.
  if [ -f "$SAN_DIR/CMakeCache.txt" ] && ! grep -q '^CMAKE_CXX_COMPILER:.*clang' "$SAN_DIR/CMakeCache.txt"; then
    rm -rf "$SAN_DIR/CMakeCache.txt" "$SAN_DIR/CMakeFiles"
  fi
  local generator=(-G "$SEDWAVE_GENERATOR")
  [ -f "$SAN_DIR/CMakeCache.txt" ] && generator=()
  cmake -S "$SEDWAVE_ROOT" -B "$SAN_DIR" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1" -DSEDWAVE_SANITIZE=ON \
    -DSEDWAVE_WERROR=ON -DSEDWAVE_BUILD_BENCH=OFF "$(sedwave_compiler_launcher)" >/dev/null
  # Before the build: test discovery runs the MPI test binaries (test_linear) at link time.
  export ASAN_OPTIONS=detect_leaks=0
  cmake --build "$SAN_DIR" -j "$JOBS" --target "${targets[@]}"
  # The programs run side by side, $JOBS at a time; each one's output is shown whole when it ends,
  # and any failure fails the pass once all have ended.
  local failed=0 running=0 t
  for t in "${SANITIZED_PROGRAMS[@]}"; do
    if [ "$running" -ge "$JOBS" ]; then
      wait -n || failed=1
      running=$((running - 1))
    fi
    (
      log="$SAN_DIR/$(basename "$t").sanitized.log"
      status=0
      "$SAN_DIR/$t" --gtest_brief=1 >"$log" 2>&1 || status=$?
      echo "== $t under AddressSanitizer + UBSan"
      cat "$log"
      exit "$status"
    ) &
    running=$((running + 1))
  done
  while [ "$running" -gt 0 ]; do
    wait -n || failed=1
    running=$((running - 1))
  done
  [ "$failed" = 0 ] || { echo "sedwave: a unit-test program failed under the sanitizers (output above)"; return 1; }
  echo "== command-line cases under AddressSanitizer + UBSan"
  (cd "$SAN_DIR" && ctest -R '^cli\.' -j "$JOBS" --output-on-failure)
}

# The two builds and their tests run side by side (each stream alone leaves the cores idle at
# times: MPI start-up, cases waiting on each other's lock, the last long compilations), GCC's
# Release build then ctest in front, the sanitizer pass behind in a log. The sanitizer pass runs
# seven unit-test programs and every command-line case, so the Release build leaves six of those
# programs out and ctest there skips the cli.* cases: nothing else compiles or runs twice. Without the
# pass (SEDWAVE_SANITIZE_TESTS=0) all of them build and run in the Release build. ctest reports as
# it goes; the pass's output follows it whole, then both verdicts (docs/performance.md, "The test
# command").
SANITIZE="${SEDWAVE_SANITIZE_TESTS:-1}"
SANITIZED_ONLY=""
CTEST_SKIP=()
if [ "$SANITIZE" = 1 ]; then
  for t in "${SANITIZED_PROGRAMS[@]##*/}"; do
    [ "$t" = test_channel_table ] || SANITIZED_ONLY="${SANITIZED_ONLY:+$SANITIZED_ONLY;}$t"
  done
  CTEST_SKIP=(-E '^cli\.')
  mkdir -p "$SAN_DIR"
  # The two builds share $JOBS compiler slots (scripts/cpu_slot.sh): no more compilers than cores,
  # the Release build's first.
  export SEDWAVE_CPU_SLOTS="$JOBS" SEDWAVE_CPU_SLOT_DIR="$SAN_DIR/cpu-slots"
  mkdir -p "$SEDWAVE_CPU_SLOT_DIR"
  # In a process group of its own (job control on for this one start), so that a failed or
  # interrupted run stops the whole pass with it.
  set -m
  (sanitizer_pass) >"$SAN_DIR/pass.log" 2>&1 &
  san_pid=$!
  set +m
  trap 'if [ -n "${san_pid:-}" ]; then kill -- -"$san_pid" 2>/dev/null || true; fi' EXIT
fi
release_status=0
sedwave_build Release -DSEDWAVE_WERROR=ON "-DSEDWAVE_SANITIZED_ONLY_TESTS=$SANITIZED_ONLY" || release_status=$?
[ "$release_status" = 0 ] && { sedwave_install_python || release_status=$?; }
ctest_status=0
if [ "$release_status" = 0 ]; then
  (cd "$BUILD_DIR" && ctest --output-on-failure -j "$JOBS" "${CTEST_SKIP[@]}" "$@") | tee "$BUILD_DIR/ctest.log" ||
    ctest_status=$?
else
  echo "sedwave: the Release build failed (output above); ctest not run" >&2
  : >"$BUILD_DIR/ctest.log"
  ctest_status=$release_status
fi
san_status=0
if [ "$SANITIZE" = 1 ]; then
  wait "$san_pid" || san_status=$?
  san_pid=""
  echo "== the sanitizer pass (build, unit-test programs, command-line cases): $SAN_DIR/pass.log"
  cat "$SAN_DIR/pass.log"
  if [ "$san_status" = 0 ]; then echo "sanitizer pass: passed"; else echo "sanitizer pass: FAILED (exit $san_status)"; fi
fi
echo "ctest on the Release build: $(grep -E 'tests passed' "$BUILD_DIR/ctest.log" || echo "no summary (exit $ctest_status)")"
[ "$ctest_status" = 0 ] && [ "$san_status" = 0 ]
