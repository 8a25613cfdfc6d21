#!/usr/bin/env bash
# Installs every Debian package bapd needs to build, test and plot.
# Safe to run repeatedly: it only calls apt-get when something is missing.
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  petsc-dev libopenmpi-dev openmpi-bin      # PETSc 3.18 (real, double) on Open MPI
  libmetis-dev                               # graph partitioning
  libhdf5-openmpi-dev                        # parallel HDF5 (fields, checkpoints)
  libgtest-dev                               # unit tests
  libyaml-dev                                # scene files are checked before PETSc reads them
  libgmsh-dev                                # body outlines from Gmsh .geo/.msh files (-body_S_type mesh)
  python3 python3-numpy python3-matplotlib python3-h5py python3-yaml  # plots, readers
  python3-paraview xvfb xauth               # tests/validation/paraview: pvpython opens fields.xdmf under Xvfb (xvfb-run)
)
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
