#!/bin/bash
# The 3D BA force rate per bond against LAMMPS peri/lps on the very same lattice
# (the target: at least half of peri/lps's per-bond rate), measured side by side in one
# run so that only the ratio is read (a shared machine moves both).
#
#   bench/kernel_bench_3d.sh [BUILD_DIR] [N] [FACTOR] [STEPS]
#
# LAMMPS `-var n N` makes (N + 1)^3 atoms; kernel_bench_3d --side N+1 the same points
# and bonds (bench/lattice_bonds.py counts them). LAMMPS's per-bond time is its Pair
# time over the timed steps (the last `run` of in.peri_lps), scaled by its own "% CPU
# use" (wall -> CPU); bapd's is thread CPU time (the minimum over repetitions).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
n=${2:-20}
factor=${3:-3.015}
steps=${4:-40}
out=/tmp/bapd_kernel_bench_3d
mkdir -p "$out"
cmake --build "$build" --target kernel_bench_3d >/dev/null
bonds=$(/usr/bin/python3 -c "import sys; sys.path.insert(0, '$here/bench'); import lattice_bonds as l; print(l.bonds($n + 1, $factor, 3))")
(cd "$out" && lmp -in "$here/bench/lammps/in.peri_lps" -var n "$n" -var factor "$factor" -var steps "$steps" \
  -log lammps.log -screen none)
pair=$(grep -E "^Pair " "$out/lammps.log" | tail -1 | awk -F'|' '{print $3}')
cpu=$(grep -E "% CPU use" "$out/lammps.log" | tail -1 | awk '{print $1}' | tr -d '%')
lammps_ns=$(/usr/bin/python3 -c "print(1e9 * $pair * $cpu / 100 / $steps / $bonds)")
"$build/bench/kernel_bench_3d" --side $((n + 1)) --factor "$factor" --table | tee "$out/bapd.txt"
/usr/bin/python3 - "$out/bapd.txt" "$lammps_ns" "$bonds" <<'PY'
import sys
r = dict(kv.split('=') for kv in open(sys.argv[1]).read().split('RESULT')[1].split())
lammps, bonds = float(sys.argv[2]), int(sys.argv[3])
assert int(r['bonds']) == bonds, (r['bonds'], bonds)
bo = float(r['bond_only_ns']) + float(r['assemble_ns'])
ec = float(r['energy_ns']) + float(r['assemble_ns'])
co = float(r['corrected_ns']) + float(r['assemble_ns'])
lbo = float(r['lanes_bond_only_ns']) + float(r['assemble_ns'])
lco = float(r['lanes_corrected_ns']) + float(r['assemble_ns'])
lec = float(r['lanes_energy_ns']) + float(r['assemble_ns'])
print(f"LAMMPS peri/lps: {lammps:.1f} ns/bond on the same {bonds} bonds")
for name, t in (("bond-only", bo), ("bond-only corrected", co), ("energy-consistent", ec),
                ("lanes bond-only", lbo), ("lanes bond-only corrected", lco), ("lanes energy-consistent", lec)):
    print(f"bapd 3D {name} force evaluation: {t:.1f} ns/bond = {lammps / t:.2f} x LAMMPS's per-bond rate (goal >= 0.5)")
PY
