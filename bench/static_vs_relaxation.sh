#!/usr/bin/env bash
# Static states two ways, side by side in one run (1 rank): the fast dynamic route
# (adaptive dynamic relaxation, each hold ended at kinetic < 1e-10 x internal energy;
# docs/options_run.md "Static states faster") and the static solver (-solver static,
# Newton; docs/options_run.md "Static solver"). CPU = user + system seconds (/usr/bin/time),
# the probes' static displacements and their relative difference, and last the two CPU
# ratios (dynamic over static) side by side. Table: docs/performance.md.
#   bench/static_vs_relaxation.sh [BAPD] [PLATE_DX] [SHEAR_DX]
# (defaults: build/bapd, the plate at dx = 1 mm, pure shear at dx = 0.5 mm; examples/).
# The runs go to $BAPD_BENCH_DIR (default ./bench_static, made afresh).
set -uo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bapd="${1:-$root/build/bapd}"
[ -x "$bapd" ] || { echo "bench: no bapd executable at '$bapd': build it, or give its path as the first argument" >&2; exit 1; }
bapd="$(realpath "$bapd")" # the runs below work in $work
plate_dx="${2:-0.001}"
shear_dx="${3:-0.0005}"
work="${BAPD_BENCH_DIR:-bench_static}"
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

plate=(-options_file_yaml "$root/examples/plate_hole.yaml" -body_dx "$plate_dx")
# Pure shear held static at stretch 1.5, 2, 3, 4, 5 (0.05 s ramps, holds of at most 1 s).
shear=(-options_file_yaml "$root/examples/pure_shear.yaml" -body_dx "$shear_dx"
       -load_schedule 0,1,0.05,1.5,1.05,1.5,1.1,2,2.1,2,2.2,3,3.2,3,3.3,4,4.3,4,4.4,5,5.4,5)
fast=(-relaxation adaptive -static_tolerance 1e-10 -output_interval 20)

run() { # NAME OPTIONS...: the run, its CPU seconds in NAME.cpu
  local name="$1"
  shift
  /usr/bin/time -f "%U %S" -o "$name.time" mpiexec -n 1 "$bapd" "$@" -progress_wall_interval 0 -output_dir "$name" > "$name.log" 2>&1 ||
    echo "bench: $name failed (see $work/$name.log)"
  awk '{print $1 + $2}' "$name.time" > "$name.cpu"
}
run plate_dynamic "${plate[@]}" -options_file_yaml "$root/examples/plate_hole_fast.yaml"
run plate_static "${plate[@]}" -solver static
run shear_dynamic "${shear[@]}" "${fast[@]}" -damping 50
run shear_static "${shear[@]}" -solver static

/usr/bin/python3 - "$plate_dx" "$shear_dx" <<'PY'
import csv, re, sys
def states(name):
    return list(csv.DictReader(open(f"{name}/static_states.csv")))
def cpu(name):
    return float(open(f"{name}.cpu").read())
def counts(name):
    text = open(f"{name}.log").read()
    m = re.search(r"(\d+) load steps .*?(\d+) Newton iterations, (\d+) Krylov.*?(\d+) tangents", text)
    if m:
        return f"{m.group(1)} load steps, {m.group(2)} Newton, {m.group(3)} Krylov iterations, {m.group(4)} tangents"
    m = re.search(r"Finished: (\d+) steps", text)
    return f"{m.group(1)} time steps" if m else "?"
print("| scene | dx (mm) | route | work | CPU (s) | static states: probe ux (mm) | largest difference | CPU ratio |")
print("|---|---|---|---|---|---|---|---|")
ratios = []
for scene, dx, probe in (("plate", sys.argv[1], "left_mid_ux_m"), ("shear", sys.argv[2], "right_mid_ux_m")):
    d, s = states(f"{scene}_dynamic"), states(f"{scene}_static")
    diff = max(abs(float(b[probe]) / float(a[probe]) - 1) for a, b in zip(d, s))
    for route, rows in (("dynamic", d), ("static", s)):
        name = f"{scene}_{route}"
        ux = ", ".join(f"{float(r['stretch']):g}: {1e3 * float(r[probe]):.4f}" for r in rows)
        ratio = f"{cpu(scene + '_dynamic') / cpu(name):.1f}" if route == "static" else "1"
        print(f"| {scene} | {1e3 * float(dx):g} | {route} | {counts(name)} | {cpu(name):.1f} | {ux} | "
              f"{'' if route == 'dynamic' else f'{diff:.1e}'} | {ratio} |")
    ratios.append(f"{scene} (dx {1e3 * float(dx):g} mm) {cpu(scene + '_dynamic') / cpu(scene + '_static'):.2f}")
print("\nCPU ratio, dynamic route over static solver: " + ", ".join(ratios))
PY
