#!/usr/bin/env bash
# Debian packages for the finite-element references in scripts/fe/ only:
#   python3-dolfinx     FEniCSx 0.5.2 (bookworm): P1/P2 elements, Newton on PETSc, MUMPS
#   python3-gmsh        gmsh's Python API: the plate's hole, the waisted sheet's shapes
#   python3-matplotlib  plots (already in scripts/install-deps.sh)
# Deliberately NOT in scripts/install-deps.sh: building, testing and running bapd never
# need them, and CI does not install them (the ctest fe.homogeneous skips without them).
# dolfinx compiles its forms at run time (FFCx + cffi), so a C compiler and the Python
# headers are needed: build-essential comes with scripts/install-deps.sh, python3-dev here.
# Safe to run repeatedly: apt-get runs only if something is missing.
set -euo pipefail
packages=(python3-dolfinx python3-gmsh python3-matplotlib python3-dev build-essential)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "install-fe-deps: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
