#!/usr/bin/env bash
# Extra Debian packages for the benchmark suite only (bench/run_all.sh):
#   lammps    the peri/lps pair style, the per-bond speed reference of bench 1
#   valgrind  callgrind instruction counts of the force kernel (reproducible on a
#             shared machine, unlike wall clock)
#   time      /usr/bin/time -v (peak resident set size)
# Deliberately NOT in scripts/install-deps.sh: building, testing and running bapd
# never need them. Safe to run repeatedly: apt-get runs only if something is missing.
set -euo pipefail
packages=(lammps valgrind time)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "install-bench-deps: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
