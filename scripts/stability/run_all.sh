#!/usr/bin/env bash
# The runs behind docs/stability.md (numerical stability at the extremes),
# then the tables: report.py rewrites the blocks between the <!-- table:NAME -->
# markers of docs/stability.md and docs/notes/stability-runs.md.
#
#   scripts/stability/run_all.sh [OUTPUT_DIR] [SECTION ...]
#
# Sections: spectrum shear rows timestep bulk horizon fracture map (default: all but
# map; map alone, the stability map of section 8, takes a few minutes:
#   scripts/stability/run_all.sh output/stability map). Each run
# is small (hundreds to a few thousand points, one rank) and is skipped when OUTPUT_DIR
# already holds it (delete OUTPUT_DIR/NAME to redo one). BAPD_EXE and BAPD_BUILD_DIR
# as in run_mpi.sh; the spectra need the build's tests/validation/stability/stability_spectrum
# (BAPD_SPECTRUM_EXE). BAPD_STABILITY_REPORT=0 skips the tables (e.g. to run sections
# side by side, then once more for the tables); BAPD_SOURCE_DIR lets a copy of this
# script run outside the source tree (bash reads a script as it runs: do not edit one
# that is running). About 80 minutes of runs (measured under load).
set -uo pipefail
here="${BAPD_SOURCE_DIR:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}"
out="${1:-$here/output/stability}"
shift || true
sections=("$@")
((${#sections[@]})) || sections=(spectrum shear rows timestep bulk horizon fracture)  # map: on request
build="${BAPD_BUILD_DIR:-$here/build}"
if [ -z "${BAPD_EXE:-}" ]; then
  "$here/scripts/install-deps.sh" --tests # (stability_spectrum is built with the tests)
  "$here/scripts/build.sh"
  export BAPD_EXE="$build/bapd"
fi
spectrum_exe="${BAPD_SPECTRUM_EXE:-$(dirname "$BAPD_EXE")/tests/validation/stability/stability_spectrum}"
ranks="${BAPD_STABILITY_RANKS:-1}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mkdir -p "$out"

# run NAME EXE OPTIONS...: one run into OUTPUT_DIR/NAME; its log is OUTPUT_DIR/NAME.log and
# OUTPUT_DIR/NAME/done holds "exit_code wall_seconds" (a run that diverges is a result, not
# an error: the tables report its message).
run() {
  local name="$1" exe="$2"; shift 2
  if [ -f "$out/$name/done" ]; then echo "== $name (cached)"; return 0; fi
  echo "== $name"
  mkdir -p "$out/$name"
  local start end rc
  start=$(date +%s.%N)
  timeout 3600 mpiexec -q -n "$ranks" --oversubscribe --bind-to none "$exe" "$@" -output_dir "$out/$name" \
    > "$out/$name.log" 2>&1
  rc=$?
  end=$(date +%s.%N)
  echo "$rc $(echo "$end - $start" | bc)" > "$out/$name/done"
  grep -E "^Stable|error:|^Finished|^Stopped|^load set top|^probe|^Static" "$out/$name.log" | cut -c1-250 || true
}
bapd() { local name="$1"; shift; run "$name" "$BAPD_EXE" "$@"; }

# Pure shear (paper scene 2) on a 1 mm grid, 70 x 10 points, pulled at 4 /s past the
# incompressible Gent limit (stretch 12.7 for Jm = 162.6) to 13.
shear=(-options_file_yaml "$here/examples/pure_shear.yaml" -body_dx 0.001 -load_schedule 0,1,3,13
       -output_interval 50 -progress_interval 1000000)
# Scene 1, the plate with a hole, on a 4 mm grid (20 x 40 points less the hole), to the
# static state at stretch 1.5 (u_max = ux of left_mid; FEA 8.62 mm).
plate=(-options_file_yaml "$here/examples/plate_hole.yaml" -body_dx 0.004 -load_schedule 0,1,1,1.5,2,1.5
       -output_interval 20 -progress_interval 1000000)

for section in "${sections[@]}"; do
  case "$section" in
  spectrum)
    # Eigenvalues of the linearised equations of motion along the pure shear path
    # (report.py: flutter growth rates, the damping they need, the stable step).
    # A small step (safety 0.2) so that the run reaches the large stretches.
    run spectrum_shear_bond_only "$spectrum_exe" "${shear[@]}" -force_form bond_only -damping 200 -time_step_safety 0.2 \
      -spectrum_stretches 1,1.5,2,2.5,3,4,5,6,7,8,9,9.5,10,10.5,11,11.5,12,12.5,13
    run spectrum_shear_energy_consistent "$spectrum_exe" "${shear[@]}" -force_form energy_consistent -damping 200 \
      -time_step_safety 0.2 -spectrum_stretches 1,1.5,2,2.5,3,3.5,4,4.25,4.5,4.75,5,6,8,10,12
    # How the flutter scales with the grid: a 20 mm wide pure shear sheet at dx = 1 and 0.5 mm.
    for dx in 0.001 0.0005; do
      run "spectrum_narrow_dx$dx" "$spectrum_exe" "${shear[@]}" -body_width 0.02 -body_dx "$dx" -force_form bond_only \
        -damping 200 -time_step_safety 0.4 -probe_right_mid_at 0.02,0.005 -spectrum_stretches 1,2,2.5,3,4
    done
    # Scene 1 (4 mm grid): small horizons, plane strain.
    for h in 1.5 2 3.015; do
      for form in bond_only energy_consistent; do
        run "spectrum_plate_h${h}_$form" "$spectrum_exe" "${plate[@]}" -horizon_factor "$h" -force_form "$form" \
          -spectrum_stretches 1,1.25,1.5
      done
    done
    run spectrum_plate_plane_strain_k100 "$spectrum_exe" "${plate[@]}" -material_formulation plane_strain \
      -material_bulk_ratio 100 -time_step_safety 0.4 -spectrum_stretches 1,1.1,1.2,1.3,1.4,1.5
    run spectrum_plate_plane_strain_k1000 "$spectrum_exe" "${plate[@]}" -material_formulation plane_strain \
      -material_bulk_ratio 1000 -time_step_safety 0.4 -spectrum_stretches 1,1.05,1.1,1.12
    run spectrum_broken "$spectrum_exe" -body_width 0.02 -body_height 0.02 -body_thickness 0.001 -body_dx 0.001 \
      -material_bulk_ratio 1000 -end_time 1 -spectrum_broken_fractions 0,0.1,0.3,0.5,0.7
    ;;
  shear)
    for c in 0 50 100 150 200 300; do bapd "shear_bond_only_c$c" "${shear[@]}" -force_form bond_only -damping "$c"; done
    for c in 0 50 200; do bapd "shear_energy_consistent_c$c" "${shear[@]}" -force_form energy_consistent -damping "$c"; done
    for safety in 0.4 0.2 0.1; do
      bapd "shear_bond_only_c200_s$safety" "${shear[@]}" -force_form bond_only -damping 200 -time_step_safety "$safety"
      bapd "shear_energy_consistent_c200_s$safety" "${shear[@]}" -force_form energy_consistent -damping 200 -time_step_safety "$safety"
    done
    ;;
  rows)
    # The order of the point rows next to the grips (row_order.py), from field files.
    for dx in 0.001 0.0005; do
      for form in bond_only energy_consistent; do
        bapd "rows_dx${dx}_$form" "${shear[@]}" -body_dx "$dx" -force_form "$form" -damping 200 -time_step_safety 0.4 \
          -end_time 0.75 -output_fields -output_fields_interval 0
      done
    done
    # Grips one horizon deep (3 point layers) on a taller sheet (the same free height).
    # The paper's placement (the sheet's own rows): grips outside by default would add
    # their rows beyond these (docs/options.md, -load_reference_length).
    bapd rows_dx0.001_layers3 "${shear[@]}" -body_height 0.016 -load_grip_placement inside -load_top_layers 3 \
      -load_bottom_layers 3 -damping 200 -load_reference_length 0.01 -time_step_safety 0.4 -end_time 0.75 -output_fields \
      -output_fields_interval 0
    ;;
  fracture)
    # torn_sheet.sh's scene (tests/validation/stability) at several steps, with and without the
    # isolated point, and paper scene 3 on a 1 mm grid as the example sets it.
    island=0.0009,0.002,0.0016,0.002,0.0016,0.002,0.0016,0.0027,0.0016,0.0027,0.0009,0.0027,0.0009,0.0027,0.0009,0.002
    torn=(-body_width 0.01 -body_height 0.01 -body_thickness 0.001 -body_dx 0.0005 -failure_critical_stretch 2
          -load_sets top,bottom -load_top_region top -load_top_x fixed -load_top_y stretch -load_bottom_region bottom
          -load_bottom_x fixed -load_bottom_y fixed -load_schedule 0,1,0.1,2,0.2,3 -damping 200
          -probes above,below -probe_above_at 0.005,0.0055 -probe_below_at 0.005,0.0045 -output_interval 1
          -progress_interval 1000000 -output_final_state)
    for safety in 0.8 0.6 0.5 0.4 0.3 0.2; do
      bapd "torn_s$safety" "${torn[@]}" -body_notches 0,0.005,0.003,0.005 -time_step_safety "$safety"
      bapd "torn_island_s$safety" "${torn[@]}" -body_notches "0,0.005,0.003,0.005,$island" -time_step_safety "$safety"
      bapd "torn_energy_consistent_s$safety" "${torn[@]}" -body_notches 0,0.005,0.003,0.005 -time_step_safety "$safety" \
        -force_form energy_consistent
    done
    # Variants whose cracks run differently: a more brittle sheet (critical stretch 1.5),
    # a softer bulk (K = 100 mu) and an island cut by a box whose corners lie on the
    # bond diagonals (so the point keeps four bonds).
    diagonal=0.001,0.002,0.0015,0.002,0.0015,0.002,0.0015,0.0025,0.0015,0.0025,0.001,0.0025,0.001,0.0025,0.001,0.002
    for safety in 0.8 0.4 0.2; do
      bapd "torn_brittle_s$safety" "${torn[@]}" -body_notches 0,0.005,0.003,0.005 -failure_critical_stretch 1.5 \
        -time_step_safety "$safety"
      bapd "torn_k100_s$safety" "${torn[@]}" -body_notches 0,0.005,0.003,0.005 -material_bulk_ratio 100 \
        -failure_critical_stretch 1.5 -time_step_safety "$safety"
      bapd "torn_diagonal_s$safety" "${torn[@]}" -body_notches "0,0.005,0.003,0.005,$diagonal" -time_step_safety "$safety"
    done
    # Scene 3 on the paper's grid (dx = 1/3 mm, 6 300 points), to stretch 3.4: the crack
    # starts near 2.9. The example's safety (0.25) and 0.4; about 6 and 4 minutes.
    for safety in 0.25 0.4; do
      bapd "notched_paper_s$safety" -options_file_yaml "$here/examples/notched_pure_shear.yaml" -time_step_safety "$safety" \
        -end_time 0.6 -progress_interval 1000
    done
    for safety in 0.8 0.4; do
      for form in bond_only energy_consistent; do
        bapd "notched_dx0.001_${form}_s$safety" -options_file_yaml "$here/examples/notched_pure_shear.yaml" -body_dx 0.001 \
          -force_form "$form" -time_step_safety "$safety" -output_final_state -progress_interval 1000000
      done
    done
    ;;
  timestep)
    # The step as a multiple of the estimated stable one (which is padded by 10 %: the
    # true limit of this scene sits near sqrt(1.1) = 1.05). With failure enabled an
    # unstable step breaks bonds instead of inverting them: the runaway-energy test
    # must stop it.
    for safety in 0.5 0.8 0.9 1.0 1.05 1.1 1.2 1.5; do
      bapd "timestep_s$safety" "${plate[@]}" -time_step_safety "$safety" -output_interval 1
    done
    for safety in 1.1 1.2 1.5; do
      bapd "timestep_failure_s$safety" "${plate[@]}" -time_step_safety "$safety" -failure_critical_stretch 7.2 -output_interval 1
    done
    ;;
  bulk)
    # Plane strain stiffens as it stretches (section 4): at the default safety 0.8 it
    # diverges before stretch 1.5 for every K; at 0.4 it reaches the static state.
    for ratio in 10 100 1000 10000; do
      bapd "bulk_plane_stress_k$ratio" "${plate[@]}" -material_bulk_ratio "$ratio"
      bapd "bulk_plane_strain_k$ratio" "${plate[@]}" -material_bulk_ratio "$ratio" -material_formulation plane_strain
      bapd "bulk_plane_strain_k${ratio}_s0.4" "${plate[@]}" -material_bulk_ratio "$ratio" -material_formulation plane_strain \
        -time_step_safety 0.4
    done
    # The bond-only form is statically unstable at rest in plane strain with K = 1000 mu
    # (section 1); the energy-consistent one is not.
    for ratio in 1000 10000; do
      bapd "bulk_plane_strain_k${ratio}_energy_consistent_s0.4" "${plate[@]}" -material_bulk_ratio "$ratio" \
        -material_formulation plane_strain -force_form energy_consistent -time_step_safety 0.4
    done
    ;;
  map)
    # The stability map (section 8): the plate on a 4 mm grid, the fast route
    # (ramps of 0.05 s, holds that end once static), one option varied at a time around
    # the default, with the step fixed at rest (the paper's, -time_step_reestimate 0)
    # and re-estimated (the default), for both force forms, each named on its command
    # line (the map does not depend on the default force form). Every cell must run to
    # the end or stop with the message that names its cause. Runs are named
    # map__VARIABLE__VALUE__FORM__RATE__STEP (report.py reads the names).
    fast=(-options_file_yaml "$here/examples/plate_hole.yaml" -options_file_yaml "$here/examples/plate_hole_fast.yaml"
          -body_dx 0.004 -output_interval 20 -progress_interval 1000000)
    to2=(-load_schedule 0,1,0.05,1.5,1.05,1.5,1.1,2.0,2.1,2.0)
    slow2=(-load_schedule 0,1,0.5,1.5,1.5,1.5,2.0,2.0,3.0,2.0)
    for step in fixed adaptive; do
      control=(); [ "$step" = fixed ] && control=(-time_step_reestimate 0)
      for form in bond_only energy_consistent; do
        for jm in 3 5 8 20 162.6; do
          bapd "map__Jm__${jm}__${form}__fast__$step" "${fast[@]}" "${to2[@]}" -material_Jm "$jm" -force_form "$form" "${control[@]}"
          bapd "map__Jm__${jm}__${form}__slow__$step" "${fast[@]}" "${slow2[@]}" -material_Jm "$jm" -force_form "$form" "${control[@]}"
        done
        for k in 10 1000 100000; do
          for formulation in plane_stress plane_strain; do
            bapd "map__bulk_ratio__${k}_${formulation}__${form}__fast__$step" "${fast[@]}" -load_schedule 0,1,0.05,1.5,0.1,1.5 \
              -material_bulk_ratio "$k" -material_formulation "$formulation" -force_form "$form" "${control[@]}"
          done
        done
        for h in 1.5 2 3.015 4; do
          bapd "map__horizon__${h}__${form}__fast__$step" "${fast[@]}" "${to2[@]}" -material_Jm 8 -horizon_factor "$h" \
            -force_form "$form" "${control[@]}"
        done
        for safety in 0.5 0.8 1.0 1.2; do
          bapd "map__safety__${safety}__${form}__fast__$step" "${fast[@]}" "${to2[@]}" -material_Jm 8 -time_step_safety "$safety" \
            -force_form "$form" "${control[@]}"
        done
      done
    done
    ;;
  horizon)
    for h in 1.5 2 2.515 3.015 3.515 4 5; do
      bapd "horizon_plate_h$h" "${plate[@]}" -horizon_factor "$h"
      bapd "horizon_plate_energy_consistent_h$h" "${plate[@]}" -horizon_factor "$h" -force_form energy_consistent
      # Paper scene 3 on a 1 mm grid (notch from the right edge): one step, for the count.
      bapd "horizon_notched_h$h" -options_file_yaml "$here/examples/notched_pure_shear.yaml" -body_dx 0.001 \
        -horizon_factor "$h" -end_time 1e-4
    done
    ;;
  esac
done
# BAPD_STABILITY_REPORT=0: runs only (e.g. sections run side by side), tables later.
if [ "${BAPD_STABILITY_REPORT:-1}" != 0 ]; then
  for doc in "$here/docs/stability.md" "$here/docs/notes/stability-runs.md"; do
    /usr/bin/python3 "$here/scripts/stability/report.py" "$out" "$doc"
  done
fi
