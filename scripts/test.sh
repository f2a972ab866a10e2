#!/usr/bin/env bash
# Set up a fresh Debian machine (as root), build with warnings as errors, run every test with ctest.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
sedwave_install_packages
sedwave_build Release -DSEDWAVE_WERROR=ON
cd "$BUILD_DIR"
# Open MPI refuses to run as root and to oversubscribe 2 cores unless told it may.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
ctest --output-on-failure -j "$JOBS" "$@"
