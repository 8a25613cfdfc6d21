#!/usr/bin/env bash
# Runs a set of short scenes with two bapd executables and compares their outputs with
# tolerance 0: every CSV the run writes (history.csv, static_states.csv, final_state.csv,
# broken_bonds.csv, ...) byte for byte, and every dataset of every field file
# (fields/step_*.h5) value for value (NaN = NaN). A refactoring that must not change a
# bit (e.g. a change to the dimension-generic core nd:: that must leave D = 2 as it
# is) is proven by "identical" on every scene.
#
#   scripts/compare_binaries.sh OLD_EXE NEW_EXE [OUT_DIR] [SCENE ...]
#
# OUT_DIR defaults to /tmp/bapd-compare; with no SCENE the eleven 2D scenes below run, with
# SCENE = 3d the four 3D ones. Runs are
# one at a time (the machine is shared), `nice -n 5`; exits 1 if any scene differs or
# fails to run with either executable.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ex="$here/examples"
old="$(realpath "${1:?usage: compare_binaries.sh OLD_EXE NEW_EXE [OUT_DIR] [SCENE ...]}")"
new="$(realpath "${2:?usage: compare_binaries.sh OLD_EXE NEW_EXE [OUT_DIR] [SCENE ...]}")"
out="${3:-/tmp/bapd-compare}"
shift $(($# < 3 ? $# : 3))
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1

fields=(-output_fields -output_fields_interval 50 -progress_interval 1000000)
# name -> "ranks|options" (the scene file first). Short schedules: each scene is a few
# hundred to a few thousand steps, long enough for breaking, warm starts, re-estimates
# and probes to have run.
declare -A scene
scene[plate_fast]="1|-options_file_yaml $ex/plate_hole.yaml -options_file_yaml $ex/plate_hole_fast.yaml -body_dx 0.002 -load_schedule 0,1,0.05,1.5,0.25,1.5"
scene[plate_fast_np2]="2|-options_file_yaml $ex/plate_hole.yaml -options_file_yaml $ex/plate_hole_fast.yaml -body_dx 0.002 -load_schedule 0,1,0.05,1.5,0.25,1.5"
scene[plate_plane_strain]="1|-options_file_yaml $ex/plate_hole.yaml -body_dx 0.002 -material_formulation plane_strain -material_bulk_ratio 100 -load_schedule 0,1,0.3,1.2"
scene[plate_bond_only_paper]="1|-options_file_yaml $ex/plate_hole.yaml -body_dx 0.002 -force_form bond_only -load_grip_placement inside -force_stress_correction none -load_schedule 0,1,0.3,1.2"
scene[plate_bond_only_tensor]="1|-options_file_yaml $ex/plate_hole.yaml -body_dx 0.002 -force_form bond_only -load_schedule 0,1,0.3,1.2"
scene[plate_scalar_failure]="1|-options_file_yaml $ex/plate_hole.yaml -body_dx 0.002 -force_form bond_only -force_stress_correction scalar -failure_critical_stretch 1.25 -load_schedule 0,1,0.3,1.6"
scene[notched_short]="1|-options_file_yaml $ex/notched_pure_shear.yaml -body_dx 0.0005 -body_width 0.035 -body_notches 0.025,0.005,0.035,0.005 -probe_notch_mouth_top_at 0.035,0.0052 -probe_notch_mouth_bottom_at 0.035,0.0048 -load_schedule 0,1,0.4,3.4 -output_interval 10 -output_final_state"
# The fracture energy's breaking passes on 2 ranks (tests/solver/fracture/budget.sh's sheet): the crack crosses it.
scene[notched_gamma_np2]="2|-options_file_yaml $ex/notched_pure_shear_gamma.yaml -body_dx 0.001 -body_width 0.03 -body_notches 0.02,0.005,0.03,0.005 -probe_notch_mouth_top_at 0.03,0.0052 -probe_notch_mouth_bottom_at 0.03,0.0048 -load_schedule 0,1,0.25,3.3 -end_time 0.25 -output_interval 10 -output_final_state"
scene[point_cloud_bond_only]="1|-options_file_yaml $ex/point_cloud.yaml -force_form bond_only -load_schedule 0,1.0,0.2,1.2 -output_final_state"
scene[point_cloud_energy]="1|-options_file_yaml $ex/point_cloud.yaml -load_schedule 0,1.0,0.2,1.2"
scene[dogbone_gmsh]="1|-options_file_yaml $ex/dogbone.yaml -body_outline_file $ex/geometry/dogbone.geo -load_schedule 0,1,0.05,1.25,0.3,1.25 -relaxation adaptive -static_tolerance 1e-10 -output_interval 20"
# 3D (run with `... OUT 3d` or by name): the block with a hole (tests/data/scenes/block_3d.yaml,
# energy-consistent, 1 and 2 ranks, and bond-only), and the notched block with
# tests/validation/notched_block_3d_short.sh's options, so that bonds break.
in3="$here/tests/data/scenes"
scene[block3d_energy]="1|-options_file_yaml $in3/block_3d.yaml -end_step 60 -output_interval 10 -output_final_state"
scene[block3d_energy_np2]="2|-options_file_yaml $in3/block_3d.yaml -end_step 60 -output_interval 10 -output_final_state"
scene[block3d_bond_only]="1|-options_file_yaml $in3/block_3d.yaml -force_form bond_only -end_step 60 -output_interval 10 -output_final_state"
scene[notched_block3d_short]="1|-options_file_yaml $ex/notched_block_3d.yaml -material_bulk_ratio 10 -failure_critical_stretch 1.5 -load_schedule 0,1,0.2,2.5 -end_step 350 -output_interval 20 -output_final_state"
order=(plate_fast plate_fast_np2 plate_plane_strain plate_bond_only_paper plate_bond_only_tensor plate_scalar_failure
       point_cloud_bond_only point_cloud_energy dogbone_gmsh notched_short notched_gamma_np2)
order3d=(block3d_energy block3d_energy_np2 block3d_bond_only notched_block3d_short)
if (($# == 1)) && [[ $1 == 3d ]]; then set -- "${order3d[@]}"; fi
(($#)) && order=("$@")

compare_h5() { # dir_a dir_b: every dataset of every fields/*.h5, exactly
  /usr/bin/python3 - "$1" "$2" <<'PY'
import glob, os, sys
import h5py, numpy as np
a, b = sys.argv[1], sys.argv[2]
fa = sorted(os.path.basename(f) for f in glob.glob(f"{a}/fields/*.h5"))
fb = sorted(os.path.basename(f) for f in glob.glob(f"{b}/fields/*.h5"))
if fa != fb: sys.exit(f"field files differ: {len(fa)} against {len(fb)}")
n = 0
for name in fa:
    with h5py.File(f"{a}/fields/{name}") as ha, h5py.File(f"{b}/fields/{name}") as hb:
        sa, sb = [], []
        ha.visititems(lambda k, o: sa.append(k) if isinstance(o, h5py.Dataset) else None)
        hb.visititems(lambda k, o: sb.append(k) if isinstance(o, h5py.Dataset) else None)
        if sorted(sa) != sorted(sb): sys.exit(f"{name}: datasets differ")
        for k in sa:
            x, y = ha[k][()], hb[k][()]
            if x.shape != y.shape or not np.array_equal(x, y, equal_nan=x.dtype.kind == "f"):
                sys.exit(f"{name}:{k} differs")
            n += 1
print(f"{len(fa)} field files, {n} datasets")
PY
}

status=0
mkdir -p "$out"
for name in "${order[@]}"; do
  spec="${scene[$name]:-}"
  [[ -n "$spec" ]] || { echo "unknown scene $name"; status=1; continue; }
  ranks="${spec%%|*}"
  read -r -a args <<<"${spec#*|}"
  ok=1
  for which in old new; do
    exe="$old"; [[ $which == new ]] && exe="$new"
    dir="$out/$name/$which"
    rm -rf "$dir" && mkdir -p "$dir"
    # An executable from before -end_step stops a run after N steps with -ts_max_steps
    # (which a newer one reports as a run cut short, exit 1).
    run_args=("${args[@]}")
    grep -q -a -e "-end_step" "$exe" || run_args=("${args[@]/#-end_step/-ts_max_steps}")
    if ! (cd "$here" && nice -n 5 mpiexec -n "$ranks" --bind-to none "$exe" "${run_args[@]}" "${fields[@]}" \
          -output_dir "$dir" > "$dir.log" 2>&1); then
      echo "FAIL  $name: the $which executable failed (tail of $dir.log):"; tail -5 "$dir.log"; ok=0
    fi
  done
  if ((ok)); then
    what=""
    for f in "$out/$name/old"/*.csv; do
      b="$(basename "$f")"
      if ! cmp -s "$f" "$out/$name/new/$b"; then what+=" $b"; fi
    done
    h5="$(compare_h5 "$out/$name/old" "$out/$name/new" 2>&1)" || what+=" fields ($h5)"
    rows=$(($(wc -l < "$out/$name/old/history.csv") - 1))
    if [[ -z "$what" ]]; then echo "identical  $name ($ranks rank(s), $rows history rows, $(ls "$out/$name/old"/*.csv | wc -l) CSV files, $h5)"
    else echo "DIFFERENT  $name:$what"; ok=0; fi
  fi
  ((ok)) || status=1
done
exit $status
