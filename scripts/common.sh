# shellcheck shell=bash
# Shared set-up for scripts/demo.sh and scripts/test.sh: install missing Debian packages, configure,
# build. Sourced, not executed. Honours BUILD_DIR (default: build) and JOBS (default: nproc).
set -euo pipefail

SEDWAVE_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$SEDWAVE_ROOT/build}"
JOBS="${JOBS:-$(nproc 2>/dev/null || echo 2)}"
# Ninja schedules the build's ~250 steps with less overhead than make; an existing build folder
# keeps the generator it was made with.
SEDWAVE_GENERATOR="${SEDWAVE_GENERATOR:-Ninja}"

# Everything sedwave needs, all Debian packages. gnuplot draws the fit plot (optional at run time);
# python3 runs the docs check (tests/docs); pybind11, Python's headers and numpy build the Python
# module (python/), pytest runs its tests.
SEDWAVE_PACKAGES=(build-essential cmake pkg-config libeigen3-dev libceres-dev libnlopt-cxx-dev libcubature-dev
  libopenmpi-dev openmpi-bin libhdf5-dev libgtest-dev libbenchmark-dev libcli11-dev libtoml11-dev
  nlohmann-json3-dev gnuplot-nox python3 ninja-build pybind11-dev python3-dev python3-numpy python3-pytest)

# Installs SEDWAVE_PACKAGES and any packages named as arguments.
sedwave_install_packages() {
  local missing=()
  local p
  for p in "${SEDWAVE_PACKAGES[@]}" "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  local line="apt-get update && apt-get install -y ${missing[*]}"
  if [ "$(id -u)" -ne 0 ]; then
    echo "sedwave: missing Debian packages. As root, run:" >&2
    echo "  $line" >&2
    exit 1
  fi
  echo "sedwave: installing ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
}

# Where ccache is installed (not required), rebuilds of unchanged sources are served from its cache;
# CCACHE_BASEDIR makes the cache shared by checkouts in different folders.
if command -v ccache >/dev/null 2>&1; then export CCACHE_BASEDIR="$SEDWAVE_ROOT"; fi

# The compiler launchers, as a CMake option: scripts/cpu_slot.sh where two builds share the cores
# (SEDWAVE_CPU_SLOT_DIR set, scripts/test.sh), then ccache where it is installed; none otherwise
# (an empty value also clears launchers a previous configuration left in the cache).
sedwave_compiler_launcher() {
  local launchers=()
  [ -n "${SEDWAVE_CPU_SLOT_DIR:-}" ] && launchers+=("$SEDWAVE_ROOT/scripts/cpu_slot.sh")
  command -v ccache >/dev/null 2>&1 && launchers+=(ccache)
  local IFS=';'
  echo "-DCMAKE_CXX_COMPILER_LAUNCHER=${launchers[*]}"
}

sedwave_build() {
  local type="${1:-Release}"
  shift || true
  local generator=(-G "$SEDWAVE_GENERATOR")
  [ -f "$BUILD_DIR/CMakeCache.txt" ] && generator=()
  cmake -S "$SEDWAVE_ROOT" -B "$BUILD_DIR" "${generator[@]}" -DCMAKE_BUILD_TYPE="$type" "$(sedwave_compiler_launcher)" "$@" >/dev/null
  cmake --build "$BUILD_DIR" -j "$JOBS"
}

# Installs the Python module into Debian's folder for locally installed packages
# (/usr/local/lib/python3.11/dist-packages), which /usr/bin/python3 searches from any folder
# (docs/python.md). As root only; a build without the module (SEDWAVE_PYTHON=OFF) installs nothing.
sedwave_install_python() {
  grep -q '^SEDWAVE_PYTHON:BOOL=ON' "$BUILD_DIR/CMakeCache.txt" 2>/dev/null || return 0
  if [ "$(id -u)" -ne 0 ]; then
    echo "sedwave: not root: the Python module stays in $BUILD_DIR/python (PYTHONPATH; docs/python.md)" >&2
    return 0
  fi
  cmake --build "$BUILD_DIR" -j "$JOBS" --target sedwave_python
  cmake --install "$BUILD_DIR" --component python >/dev/null
  echo "sedwave: Python module installed: /usr/bin/python3 -c 'import sedwave' works in any folder" >&2
}
