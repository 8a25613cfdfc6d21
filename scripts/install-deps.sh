#!/usr/bin/env bash
# Installs the Debian packages bapd needs, in two sets:
#   scripts/install-deps.sh           to build and run bapd and plot its results
#                                     (run_mpi.sh, scripts/validation/run_all.sh)
#   scripts/install-deps.sh --tests   the same, and what the test suite needs on top
#                                     (scripts/test.sh, .ci/run)
# Safe to run repeatedly: it only calls apt-get when something is missing.
set -euo pipefail
run_packages=(
  build-essential cmake pkg-config
  petsc-dev libopenmpi-dev openmpi-bin      # PETSc 3.18 (real, double) on Open MPI
  libmetis-dev                               # graph partitioning
  libhdf5-openmpi-dev                        # parallel HDF5 (fields, checkpoints)
  libyaml-dev                                # scene files are checked before PETSc reads them
  libgmsh-dev                                # body outlines from Gmsh .geo/.msh files (-body_S_type mesh)
  python3 python3-numpy python3-matplotlib   # scripts/plot_history.py, bapd-fit's plots
  python3-h5py                               # scripts/plot_fields.py and the validation report read the field files
)
test_packages=(
  libgtest-dev                               # the unit tests (GoogleTest)
  python3-paraview xvfb xauth                # tests/validation/paraview: pvpython opens fields.xdmf under Xvfb (xvfb-run)
)
packages=("${run_packages[@]}")
case "${1:-}" in
  "") ;;
  --tests) packages+=("${test_packages[@]}") ;;
  *) echo "install-deps.sh: error: unknown argument '$1': give nothing (to run bapd) or --tests (to run the test suite too)" >&2; exit 2 ;;
esac
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "install-deps: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
