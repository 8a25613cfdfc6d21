#!/usr/bin/env bash
# The whole test suite from a fresh machine: install what running and testing need,
# build everything (the tests switched on, also in a build directory run_mpi.sh
# configured without them), run every test.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$here/scripts/install-deps.sh" --tests
"$here/scripts/build.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
cd "${BAPD_BUILD_DIR:-$here/build}"
# Tests declare the ranks they use (PROCESSORS): ctest runs as many side by side as
# the machine has cores.
ctest --output-on-failure --timeout 600 -j "$(nproc)" "$@"
