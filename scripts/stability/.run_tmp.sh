#!/usr/bin/env bash
# The runs behind docs/stability.md (issue 6: numerical stability at the extremes),
# then the tables: report.py rewrites the blocks between the <!-- table:NAME -->
# markers of docs/stability.md.
#
#   scripts/stability/run_all.sh [OUTPUT_DIR] [SECTION ...]
#
# Sections: spectrum shear timestep bulk horizon broken (default: all). Each run
# is small (hundreds to a few thousand points, one rank) and is skipped when OUTPUT_DIR
# already holds it (delete OUTPUT_DIR/NAME to redo one). BAPD_EXE and BAPD_BUILD_DIR
# as in run_mpi.sh; the spectra need the build's tests/stability/stability_spectrum.
# About 40 minutes on one quiet core.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
out="${1:-$here/output/stability}"
shift || true
sections=("$@")
((${#sections[@]})) || sections=(spectrum shear timestep bulk horizon broken)
build="${BAPD_BUILD_DIR:-$here/build}"
if [ -z "${BAPD_EXE:-}" ]; then
  "$here/scripts/install-deps.sh"
  "$here/scripts/build.sh"
  export BAPD_EXE="$build/bapd"
fi
spectrum_exe="${BAPD_SPECTRUM_EXE:-$(dirname "$BAPD_EXE")/tests/stability/stability_spectrum}"
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
    for form in bond_only energy_consistent; do
      run "spectrum_shear_$form" "$spectrum_exe" "${shear[@]}" -force_form "$form" -damping 200 \
        -spectrum_stretches 1,1.5,2,3,4,5,6,8,10,12
    done
    run spectrum_broken "$spectrum_exe" -body_width 0.02 -body_height 0.02 -body_thickness 0.001 -body_dx 0.001 \
      -material_bulk_ratio 1000 -end_time 1 -spectrum_broken_fractions 0,0.1,0.3,0.5,0.7
    ;;
  shear)
    for c in 0 50 100 150 200 300; do bapd "shear_bond_only_c$c" "${shear[@]}" -force_form bond_only -damping "$c"; done
    for c in 0 50 200; do bapd "shear_energy_consistent_c$c" "${shear[@]}" -force_form energy_consistent -damping "$c"; done
    bapd shear_bond_only_c200_s0.4 "${shear[@]}" -force_form bond_only -damping 200 -time_step_safety 0.4
    ;;
  esac
done
true
