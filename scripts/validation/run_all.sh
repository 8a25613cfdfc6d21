#!/usr/bin/env bash
# Regenerates sections 1-4 of docs/validation.md: runs the paper's three scenes (docs/method.md section 7),
# then tabulates and plots them. Long (about an hour on 2 cores); not part of the
# test suite. Usage: scripts/validation/run_all.sh [ranks] [output root] [case names]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
ranks="${1:-2}"
out="${2:-$here/output/validation}"
mkdir -p "$out"
if [ -z "${BAPD_EXE:-}" ]; then
  "$here/scripts/install-deps.sh"
  "$here/scripts/build.sh" --run
  export BAPD_EXE="${BAPD_BUILD_DIR:-$here/build}/bapd"
fi

run() { # name, scene, options...: runs once, records the wall time
  local name="$1" scene="$2"; shift 2
  want "$name" || return 0
  if [ -f "$out/$name/done" ]; then echo "== $name (cached)"; return; fi
  echo "== $name"
  local start end
  start=$(date +%s.%N)
  if ! /usr/bin/time -f "%U %S" -o "$out/$name.cpu" "$here/run_mpi.sh" -n "$ranks" "$scene" -output_dir "$out/$name" "$@" > "$out/$name.log" 2>&1; then
    echo "   FAILED (see $out/$name.log):"; grep "bapd: error" "$out/$name.log" | tail -1
    return 0 # the report shows what finished
  fi
  end=$(date +%s.%N)
  # ranks, wall seconds, CPU seconds of all ranks (user + system, from /usr/bin/time)
  echo "$ranks $(echo "$end - $start" | bc) $(awk '{print $1 + $2}' "$out/$name.cpu")" > "$out/$name/done"
  grep -E "^Static|^probe|^load set" "$out/$name.log" || true
}

# Cases to run: all, or a list of names (e.g. "plate_dx2_h3.015 pure_shear").
only="${3:-all}"
want() { [ "$only" = all ] || [[ " $only " == *" $1 "* ]]; }

# In order of what the report needs most, so that a run cut short still has the
# accuracy figures.
# Scene 1: plate with a hole, static states at stretch 1.5, 1.75, 2.0 by the fast
# route (examples/plate_hole_fast.yaml: 0.05 s ramps, adaptive dynamic relaxation,
# holds end once kinetic energy < 1e-10 x internal energy), three horizons.
fast=(-options_file_yaml "$here/examples/plate_hole_fast.yaml")
for h in 3.015 2.515 3.515; do
  run "plate_dx1_h$h" "$here/examples/plate_hole.yaml" "${fast[@]}" -horizon_factor "$h" -output_interval 40
done
# Pure shear's static states at stretch 1.5, 2, 3 against the FE solution of the
# clamped 70 mm x 10 mm free region (docs/fe_reference.md: 5.417, 8.591, 14.065 kPa), and with
# grips 4, 8 and 12 rows deep instead of the default two horizons (6 rows): the
# stress must not depend on the depth, nor the rows next to a grip be overstretched.
static=(-load_schedule 0,1,0.05,1.5,1.05,1.5,1.1,2,2.1,2,2.2,3,3.2,3 -relaxation adaptive -static_tolerance 1e-10 -output_interval 20 -output_final_state)
run pure_shear_static_dx0.5 "$here/examples/pure_shear.yaml" "${static[@]}"
run pure_shear_static_dx1 "$here/examples/pure_shear.yaml" "${static[@]}" -body_dx 0.001
for n in 4 8 12; do
  run "pure_shear_static_dx0.5_rows$n" "$here/examples/pure_shear.yaml" "${static[@]}" -load_top_layers "$n" -load_bottom_layers "$n"
done
for h in 3.015 2.515 3.515; do
  run "plate_dx2_h$h" "$here/examples/plate_hole.yaml" -body_dx 0.002 "${fast[@]}" -horizon_factor "$h"
done
# The paper's method (one rigid row inside per grip, the uncorrected bond-only force):
# its Table 1 row, next to the defaults.
paper=(-force_form bond_only -load_grip_placement inside -force_stress_correction none)
run plate_dx2_h3.015_paper "$here/examples/plate_hole.yaml" -body_dx 0.002 "${fast[@]}" "${paper[@]}"
run plate_dx1_h3.015_paper "$here/examples/plate_hole.yaml" "${fast[@]}" "${paper[@]}" -output_interval 40
run pure_shear_static_dx0.5_paper "$here/examples/pure_shear.yaml" "${static[@]}" "${paper[@]}"
# Scene 2: pure shear to stretch 5.125; scene 3: notched pure shear with failure, with
# the defaults and with the paper's grips (one rigid row inside, the stretch over the
# whole 10 mm height; the scene's force form).
run pure_shear "$here/examples/pure_shear.yaml"
run notched_pure_shear "$here/examples/notched_pure_shear.yaml" -output_fields -output_fields_interval 500 -output_interval 50
run notched_pure_shear_paper_grips "$here/examples/notched_pure_shear.yaml" -load_grip_placement inside -force_stress_correction none \
  -output_fields -output_fields_interval 500 -output_interval 50
# The slow explicit route (the scene's 1 s ramps, full holds, fixed damping: the
# paper's way) to check the fast one.
run plate_dx2_h3.015_slow "$here/examples/plate_hole.yaml" -body_dx 0.002 -static_tolerance 0
for h in 3.015 2.515 3.515; do
  run "plate_dx0.5_h$h" "$here/examples/plate_hole.yaml" "${fast[@]}" -body_dx 0.0005 -horizon_factor "$h" -output_interval 80
done
# Shaped specimens against their FE solutions (docs/fe_reference.md), static
# states by the fast route at the FE's stretches (scripts/validation/shaped_report.py).
shaped=(-relaxation adaptive -static_tolerance 1e-10 -output_interval 20)
run waisted_static "$here/examples/waisted_sheet.yaml" "${shaped[@]}" \
  -load_schedule 0,1,0.05,1.25,1.05,1.25,1.1,1.5,2.1,1.5,2.15,1.75,3.15,1.75,3.2,2,4.2,2
run dogbone_static "$here/examples/dogbone.yaml" "${shaped[@]}" -body_outline_file "$here/examples/geometry/dogbone.geo" \
  -load_schedule 0,1,0.05,1.25,1.05,1.25,1.1,1.5,2.1,1.5

/usr/bin/python3 "$here/scripts/validation/report.py" "$out" "$here/docs"
