#!/usr/bin/env bash
# Bad input: each mistake, run on RANKS ranks, must stop with a non-zero exit code
# within 60 s, print exactly one error line that contains the expected text (the option
# and the fix), and print no PETSc error stack, no crash. On more ranks every case runs
# through run_mpi.sh; on 1 rank only the cases about run_mpi.sh's own command line do
# (see the launch below), the rest run bapd alone.
#   bad_input.sh RANKS [PART]   (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
# PART (options, geometry, sets; default all) runs one part of the cases, so that ctest
# can run the parts side by side: each case starts bapd, and MPI and PETSc with it.
# On 1 rank every case runs; on more ranks the parallel sample below: every rank builds
# the scene and checks it alike, so most cases take the 1-rank path on each rank and
# another rank count proves nothing new about them.
set -uo pipefail
ranks="$1"
only="${2:-all}"
source_dir="$BAPD_SOURCE_DIR"
fixtures="$source_dir/tests/data/scenes"
run_mpi="$source_dir/run_mpi.sh"
work="input_bad_input_np${ranks}_$only"
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
scene="$fixtures/tiny.yaml"
failures=0
cases=0
# On one rank nothing else is left to stop when bapd exits with its error, yet Open MPI's
# mpiexec waits odls_base_sigkill_timeout (1 s, twice: 2.1 s a case) before it returns
# after a non-zero exit; 0 makes a case ~0.6 s. Not on more ranks: there the other
# ranks get that second to finish what they print.
((ranks == 1)) && export OMPI_MCA_odls_base_sigkill_timeout=0

# The parallel sample: the cases whose path differs on more than one rank, and one of
# each kind of check that every rank makes alike. Rank 0 alone looks and broadcasts
# what it found for the memory estimate (dx_needs_more_memory, cloud_needs_more_memory),
# the output directory (output_dir_*), a checkpoint's header (restart_*), the options
# left unused (unknown_option) and the pieces of a partitioned body (cloud_two_pieces);
# PETSc's own option errors are collective (petsc_*); every rank reads the same file at
# once (yaml_*, mesh_not_gmsh, group_missing, cloud_unreadable, cloud_duplicate);
# bapd without run_mpi.sh (no_scene); a check of the scene, the body, a 3D body, a load
# set, a probe and the patch correction (negative_dx, shape_cuts_apart, body_3d_patch,
# empty_load_set, curve_selects_nothing, probe_block_many, patch_correction_energy).
parallel_sample=" no_scene yaml_syntax yaml_alias_bomb unknown_option petsc_real petsc_ts_type negative_dx
  body_3d_patch dx_needs_more_memory empty_load_set output_dir_proc output_dir_under_file restart_missing
  restart_truncated restart_other_body shape_cuts_apart mesh_not_gmsh
  group_missing curve_selects_nothing cloud_unreadable cloud_duplicate cloud_two_pieces probe_block_many
  cloud_needs_more_memory patch_correction_energy restart_other_dimension compression_folds mesh_size_max width_huge "
in_sample() { ((ranks == 1)) || [[ " $(echo $parallel_sample) " == *" $1 "* ]]; }
# (A name in the sample that no case below has would leave its path untried: refused.)
for name in $parallel_sample; do
  grep -qE "expect_error $name( |$)" "${BASH_SOURCE[0]}" || { echo "FAIL: the parallel sample names '$name', which is no case"; exit 1; }
done

# part NAME: the cases below belong to part NAME.
part() { current_part="$1"; }
in_part() { [ "$only" = all ] || [ "$only" = "$current_part" ]; }

# The launch on 1 rank: bapd alone, an MPI singleton, its first argument (a .yaml file)
# the scene, as run_mpi.sh would pass it. On 1 rank run_mpi.sh reaches the same bapd with
# the same arguments and adds its own checks and mpiexec's start: a case took 2.0 s
# (0.66 s of CPU) through it, 1.1 s (0.40 s) alone. run_mpi.sh's own part is its command
# line, which the cases named here try (as every case on more ranks does). Isolated: no
# orted is forked for the singleton, which needs none (a plain singleton's took 2.1 s).
# Every isolated singleton takes job family 0, so that two at once (two parts side by
# side under ctest -j) would share their session directory under TMPDIR, and one's
# clean-up could remove it while the other's MPI_Init creates a file in it ("A call to
# mkdir was unable to create the desired directory"): each part's singletons get a
# TMPDIR of their own.
singleton_tmp="$(mktemp -d)" || exit 1
trap 'rm -rf "$singleton_tmp"' EXIT
through_run_mpi=" missing_scene device_scene missing_second_scene stray_argument bad_rank_count "
for name in $through_run_mpi; do
  grep -qE "expect_error $name( |$)" "${BASH_SOURCE[0]}" || { echo "FAIL: through_run_mpi names '$name', which is no case"; exit 1; }
done
# expect_error NAME TEXT ARGS...: run_mpi.sh -n RANKS ARGS... (on 1 rank: bapd alone, but
# for the cases through_run_mpi names) must fail as described (with BAPD_DIRECT=1:
# mpiexec -n RANKS bapd ARGS..., for what run_mpi.sh would not pass on).
expect_error() {
  local name="$1" text="$2" rc problems=""
  shift 2
  in_part && in_sample "$name" || return 0
  cases=$((cases + 1))
  local launch=("$run_mpi" -n "$ranks")
  if ((ranks == 1)) && [[ "$through_run_mpi" != *" $name "* ]] && [[ "${1:-}" == *.yaml ]]; then
    launch=(env TMPDIR="$singleton_tmp" OMPI_MCA_ess_singleton_isolated=1 "$BAPD_EXE" -options_file_yaml)
  fi
  [ -n "${BAPD_DIRECT:-}" ] && launch=(mpiexec -q -n "$ranks" --oversubscribe "$BAPD_EXE")
  timeout 60 "${launch[@]}" "$@" > "$name.log" 2>&1
  rc=$?
  if ((rc == 124)); then problems+=" timed out (hang?);"
  elif ((rc == 0)); then problems+=" exit code 0;"
  elif ((rc >= 128)); then problems+=" killed by signal $((rc - 128));"
  fi
  grep -qF -- "$text" "$name.log" || problems+=" no '$text' in the output;"
  local errors
  errors=$(grep -c "error:" "$name.log")
  ((errors == 1)) || problems+=" $errors error lines instead of 1;"
  grep -q "PETSC ERROR" "$name.log" && problems+=" a PETSc error stack;"
  grep -qiE "Segmentation|core dumped|Caught signal|MPI_ABORT" "$name.log" && problems+=" a crash or an abort;"
  if [ -n "$problems" ]; then
    echo "FAIL $name (np $ranks, exit $rc):$problems"
    sed 's/^/    | /' "$name.log"
    failures=$((failures + 1))
  else
    echo "ok   $name: $(grep "error:" "$name.log")"
  fi
}

part options
# The scene file and the command line
expect_error missing_scene "cannot open scene file 'no_such_scene.yaml'" no_such_scene.yaml
expect_error device_scene "'/dev/zero' (-options_file_yaml) is a device" "$scene" -options_file_yaml /dev/zero
# bapd with options but no scene (run_mpi.sh would run the default scene under them)
BAPD_DIRECT=1 expect_error no_scene "no scene was given: give a scene file, e.g. mpiexec -n 2 bapd -options_file_yaml examples/default.yaml" \
  -output_dir no_scene -end_step 10
expect_error missing_second_scene "cannot open scene file 'no_such_scene.yaml'" "$scene" -options_file_yaml no_such_scene.yaml
expect_error missing_options_file "cannot open options file 'no_such_options.txt'" "$scene" -options_file no_such_options.txt
expect_error yaml_syntax "is not valid YAML" "$fixtures/bad_syntax.yaml"
# Scenes built to exhaust the reader: 1e5 nested brackets (libyaml's cost grows with the
# square of the depth), sections nested past PETSc's 25 prefixes, aliases of aliases that
# expand to 9^9 values, and a file far larger than a scene.
if in_part; then
  /usr/bin/python3 -c "print('body:\n  dx: 0.001\nx: ' + '[' * 100000 + ']' * 100000)" > deep_list.yaml
  /usr/bin/python3 -c "print('material: ' + '{a: ' * 40 + '1' + '}' * 40)" > deep_sections.yaml
  /usr/bin/python3 -c "
print('a: &a {x: 1, y: 1, z: 1, u: 1, v: 1, w: 1, p: 1, q: 1, r: 1}')
for i in range(1, 9):
    print(f'a{i}: &a{i} {{' + ', '.join(f'k{k}: *a' + (str(i - 1) if i > 1 else '') for k in range(9)) + '}')" > alias_bomb.yaml
  /usr/bin/python3 -c "print('body_dx: 0.001\n' + '# padding\n' * 200000)" > huge_scene.yaml
fi
expect_error yaml_deep_list "'deep_list.yaml': sections are nested more than 8 levels deep at line 3" deep_list.yaml
expect_error yaml_deep_sections "'deep_sections.yaml': sections are nested more than 8 levels deep at line 1" deep_sections.yaml
expect_error yaml_alias_bomb "'alias_bomb.yaml': it expands to more than 100000 values through its aliases" alias_bomb.yaml
expect_error yaml_huge_scene "scene file 'huge_scene.yaml' holds 2000016 bytes, more than a scene's 1048576" huge_scene.yaml
expect_error stray_argument "unexpected argument 'scene.txt'" "$scene" scene.txt
expect_error bad_rank_count "-n needs a number of ranks" "$scene" -n two

# Unknown options: the nearest real name
expect_error unknown_option "-material_muu is not a bapd option. Did you mean -material_mu?" "$scene" -material_muu 5e3
expect_error nested_key "(-body_dx_value was given: in YAML, 'value' is nested under the key of -body_dx" "$fixtures/nested_key.yaml"
expect_error time_step_typo "-time_step_reestimat is not a bapd option. Did you mean -time_step_reestimate?" "$scene" -time_step_reestimat 10
expect_error nested_optional_key "-material_mu_value is not a bapd option. In YAML, 'value' is nested under the key of -material_mu" "$scene" -material_mu_value 3
expect_error duplicate_key "key 'width' is given twice under 'body' (lines 3 and 7): give each key once" "$fixtures/duplicate_key.yaml"
expect_error misspelt_required "(-body_widht was given: is it a misspelling of -body_width?)" "$fixtures/misspelt_width.yaml"

# Wrong types, bapd's options and PETSc's
expect_error real_not_number "-body_dx 'abc' is not a number" "$scene" -body_dx abc
expect_error int_not_whole "-output_interval '1.5' is not a whole number" "$scene" -output_interval 1.5
expect_error list_not_numbers "-body_holes '0.005,x,0.001': 'x' is not a number" "$scene" -body_holes 0.005,x,0.001
expect_error petsc_real "-ts_dt 'abc' is not valid: give a number" "$scene" -ts_dt abc
expect_error petsc_int "-ts_max_steps '1.5' is not valid: give a whole number" "$scene" -ts_max_steps 1.5
expect_error petsc_ts_type "Unknown TS type" "$scene" -ts_type nosuch
expect_error petsc_bool "-output_final_state 'maybe' is not valid: give true or false" "$scene" -output_final_state maybe

# Non-physical values
expect_error negative_dx "-body_dx -0.0005: the lattice spacing must be > 0 m" "$scene" -body_dx -0.0005
expect_error zero_width "-body_width 0: the sheet width along x must be > 0 m" "$scene" -body_width 0
expect_error negative_thickness "-body_thickness -0.001: the sheet thickness must be > 0 m" "$scene" -body_thickness -0.001
expect_error zero_output_interval "-output_interval 0" "$scene" -output_interval 0
expect_error critical_stretch_inf "-failure_critical_stretch 'inf' is not a finite number: give one value in SI units, e.g. -failure_critical_stretch 7.2" "$scene" -failure_critical_stretch inf
expect_error huge_modulus "-material_mu 1e+308 Pa is too large" "$scene" -material_mu 1e308
expect_error monitor_reference_negative "-time_step_monitor_reference -1: give the force evaluations" "$scene" -time_step_monitor_reference -1
expect_error grip_depth_huge "-load_top_depth 1e+30 m is 1000000000 row(s), 500000 m deep, more than ten times the body's height (0.01 m)" \
  "$scene" -load_top_depth 1e30
expect_error tiny_modulus "-material_mu 1e-300 Pa is far below any solid's shear modulus" "$scene" -material_mu 1e-300
expect_error huge_bulk_ratio "-material_bulk_ratio 1e+30 is beyond what double precision resolves" "$scene" -material_bulk_ratio 1e30
expect_error end_time_huge "-end_time 1e+300 s needs at least" "$scene" -end_time 1e300
expect_error end_time_huge_step "-end_time 1e+06 s needs 1e+15 time steps with -time_step 1e-09 s" "$scene" -end_time 1e6 -time_step 1e-9
expect_error compression_folds "Cause: the compression (applied stretch" "$scene" -load_schedule 0,1,0.01,0.1
expect_error critical_stretch_one "-failure_critical_stretch 1: a bond breaks once stretched past s_c, so s_c must be > 1" "$scene" -failure_critical_stretch 1
expect_error critical_stretch_below "-failure_critical_stretch 0.5" "$scene" -failure_critical_stretch 0.5
expect_error fracture_energy_zero "-failure_fracture_energy 0: the fracture energy Gamma must be > 0 J/m^2" "$scene" -failure_fracture_energy 0
expect_error two_failure_criteria "-failure_critical_stretch 7.2 and -failure_fracture_energy 165: give one failure criterion" "$scene" -failure_critical_stretch 7.2 -failure_fracture_energy 165
expect_error tip_concentration_above_one "-failure_tip_concentration 2: kappa is a fraction in (0, 1]" "$scene" -failure_fracture_energy 165 -failure_tip_concentration 2
expect_error horizon_below_dx "-horizon_factor 0.5 is below 1" "$scene" -horizon_factor 0.5
expect_error bad_relaxation "-relaxation 'fast' is not a relaxation route: choose none (fixed -damping) or adaptive" "$scene" -relaxation fast

part geometry
# Geometry
# A 3D body: the 2D-only material options refused, each with its message
expect_error body_3d_formulation "-material_formulation plane_strain is a 2D reduction" "$fixtures/block_3d.yaml" -material_formulation plane_strain
# -force_patch_correction runs in 3D (tests/mpi/box_3d.sh patch_cloud); what stays refused there as
# in 2D: a correction of the energy-consistent form (the default), on and virial alike
expect_error body_3d_patch "-force_patch_correction on corrects the bond-only force only" "$fixtures/block_3d.yaml" -force_patch_correction on
expect_error body_3d_patch_virial "-force_patch_correction virial corrects the bond-only force only" "$fixtures/block_3d.yaml" \
  -force_form energy_consistent -force_patch_correction virial
expect_error body_3d_box "-body_block_box holds 4 numbers: a 3D box takes six" "$fixtures/block_3d.yaml" -body_block_box 0,0,0.01,0.008
expect_error hole_covers_body "-body_holes: hole 1 (centre (0.005, 0.005) m, radius 0.02 m) covers the whole body" "$scene" -body_holes 0.005,0.005,0.02
expect_error hole_misses_body "-body_holes: hole 1 (centre (0.02, 0.02) m, radius 0.001 m) does not reach the body" "$scene" -body_holes 0.02,0.02,0.001
expect_error notch_outside "-body_notches: notch 1 ends at (0.02, 0.005) m, outside the body" "$scene" -body_notches 0.02,0.005,0.008,0.005
# 1e5 x 1e5 cells of the sheet and 2 x 6 rows of 1e5 of the grips outside it (two horizons deep)
expect_error dx_needs_more_memory "-body_dx 1e-07 m asks for about 10001200000 material points" "$scene" -body_dx 1e-7
expect_error width_huge "-body_width 1e+308 m and -body_height 0.01 m at -body_dx 0.0005 m make a lattice of inf points" \
  "$scene" -body_width 1e308
expect_error dx_tiny "-body_width 0.01 m and -body_height 0.01 m at -body_dx 1e-300 m make a lattice of inf points" \
  "$scene" -body_dx 1e-300
expect_error dx_above_body "-body_dx 0.02 m is larger than the body" "$scene" -body_dx 0.02
expect_error empty_load_set "-load_mid_box 0.001,0.001,0.0011,0.0011 selects no material point for load set 'mid'" \
  "$scene" -load_sets top,bottom,mid -load_mid_region box -load_mid_box 0.001,0.001,0.0011,0.0011 -load_mid_x fixed

# Output that cannot be written
long_dir="$PWD/$(printf 'd%.0s' $(seq 200))"
for _ in $(seq 20); do long_dir="$long_dir/$(printf 'd%.0s' $(seq 200))"; done
expect_error output_dir_too_long "characters) (File name too long): choose a writable directory" "$scene" -output_dir "$long_dir"
expect_error output_dir_proc "-output_dir /proc/forbidden" "$scene" -output_dir /proc/forbidden
expect_error output_dir_under_file "-output_dir $fixtures/tiny.yaml/out cannot be created or written: '$fixtures/tiny.yaml' is a file" \
  "$scene" -output_dir "$fixtures/tiny.yaml/out"

# Restart files that do not fit
expect_error restart_missing "-restart" "$scene" -restart no_such_checkpoint.h5
if [ -f "$source_dir/include/bapd/solver/io/checkpoint.hpp" ]; then
  # A good checkpoint of the tiny scene, then a copy cut short and a run of another body.
  if ! in_part; then :
  elif timeout 60 "$run_mpi" -n "$ranks" "$scene" -output_dir good -checkpoint_interval 20 > good.log 2>&1 && [ -f good/checkpoint.h5 ]; then
    head -c 20000 good/checkpoint.h5 > truncated.h5
    expect_error restart_truncated "Checkpoint 'truncated.h5' cannot be read" "$scene" -restart truncated.h5 -output_dir truncated
    expect_error restart_not_hdf5 "Checkpoint '$scene' cannot be read" "$scene" -restart "$scene" -output_dir not_hdf5
    expect_error restart_other_dimension "Checkpoint 'good/checkpoint.h5' holds a 2D body and this scene is 3D (-body_dimension 3)" \
      "$fixtures/block_3d.yaml" -restart good/checkpoint.h5 -output_dir other_dimension
    if /usr/bin/python3 -c "import h5py" 2> /dev/null; then # one bit of an attribute no checksum covers
      cp good/checkpoint.h5 flipped_dx.h5
      /usr/bin/python3 -c "
import h5py, numpy
with h5py.File('flipped_dx.h5', 'r+') as f:
    a = numpy.array([f['geometry'].attrs['dx_m']]); a.view(numpy.uint8)[0] ^= 1; f['geometry'].attrs['dx_m'] = a[0]"
      expect_error restart_flipped_dx "Checkpoint 'flipped_dx.h5' holds this body's points and bonds, but its attributes say dx" \
        "$scene" -restart flipped_dx.h5 -output_dir flipped_dx
    fi
    expect_error restart_other_body "Checkpoint 'good/checkpoint.h5' belongs to another body" \
      "$scene" -restart good/checkpoint.h5 -body_dx 0.001 -end_time 0.02 -output_dir other
  else
    echo "FAIL checkpoint: the tiny scene did not write good/checkpoint.h5"
    cat good.log
    failures=$((failures + 1))
  fi
fi

# Shapes (shape.hpp): each mistake named with the shape's option
sh=(-body_shapes cut)
expect_error shape_no_type "-body_cut_type is required for shape 'cut'" "$scene" "${sh[@]}" -body_cut_box 0,0,0.001,0.001
expect_error shape_bad_type "-body_cut_type 'square' is not a shape" "$scene" "${sh[@]}" -body_cut_type square
expect_error shape_bad_op "-body_cut_op 'minus': give subtract, add or intersect" "$scene" "${sh[@]}" -body_cut_type circle \
  -body_cut_centre 0,0 -body_cut_radius 0.002 -body_cut_op minus
expect_error shape_stray_parameter "-body_cut_radius is not a parameter of a rectangle" "$scene" "${sh[@]}" -body_cut_type rectangle \
  -body_cut_box 0,0,0.002,0.002 -body_cut_radius 0.001
expect_error shape_self_crossing "-body_cut_points: edges 1 and 3 cross" "$scene" "${sh[@]}" -body_cut_type polygon \
  -body_cut_points 0.002,0.002,0.008,0.008,0.008,0.002,0.002,0.006
expect_error shape_misses_body "-body_cut: the circle holds no lattice point of the sheet" "$scene" "${sh[@]}" -body_cut_type circle \
  -body_cut_centre 0.5,0.5 -body_cut_radius 0.001
expect_error shape_cuts_apart "-body_shapes: the body falls apart into 2 pieces" "$scene" "${sh[@]}" -body_cut_type rectangle \
  -body_cut_box -1,0.004,1,0.006
expect_error shape_reserved_name "-body_shapes: 'width' is the name of a body option" "$scene" -body_shapes width
expect_error shape_undeclared "'hole2' is not one of -body_shapes" "$scene" "${sh[@]}" -body_cut_type circle -body_cut_centre 0,0 \
  -body_cut_radius 0.002 -body_hole2_radius 0.001
# (every option of a shape's table counts, -body_S_discretisation the last of them)
expect_error shape_undeclared_discretisation "'hole2' is not one of -body_shapes" "$scene" "${sh[@]}" -body_cut_type circle \
  -body_cut_centre 0,0 -body_cut_radius 0.002 -body_hole2_discretisation centroids
expect_error mesh_missing_file "-body_cut_file: cannot open 'no_such.geo'" "$scene" "${sh[@]}" -body_cut_type mesh -body_cut_file no_such.geo
expect_error mesh_device "-body_cut_file: '/dev/zero' is a device" "$scene" "${sh[@]}" -body_cut_type mesh -body_cut_file /dev/zero
expect_error mesh_tiny_size "-body_cut: the mesh holds no lattice point of the sheet" "$scene" "${sh[@]}" -body_cut_type mesh \
  -body_cut_file "$source_dir/tests/data/geometry/tiny_mesh_size.geo"
expect_error mesh_size_max "-body_cut: the mesh holds no lattice point of the sheet" "$scene" "${sh[@]}" -body_cut_type mesh \
  -body_cut_file "$source_dir/tests/data/geometry/tiny_mesh_size_max.geo"
expect_error mesh_no_surface "-body_cut_file: '$source_dir/tests/data/geometry/lines_only.geo' holds no surface" "$scene" "${sh[@]}" \
  -body_cut_type mesh -body_cut_file "$source_dir/tests/data/geometry/lines_only.geo"
expect_error mesh_not_gmsh "-body_cut_file: Gmsh cannot read" "$scene" "${sh[@]}" -body_cut_type mesh -body_cut_file "$source_dir/tests/data/geometry/broken.geo"
expect_error mesh_no_file "-body_cut_file: give the Gmsh .geo or .msh file" "$scene" "${sh[@]}" -body_cut_type mesh
expect_error probe_in_shape "lies where shape 'cut' (subtract) removed the material" "$scene" "${sh[@]}" -body_cut_type circle \
  -body_cut_centre 0.005,0.005 -body_cut_radius 0.002 -probes p -probe_p_at 0.005,0.005

part sets
# Load sets by polygon, curve and Gmsh physical group (scene_loading.hpp)
den=(-body_shapes o -body_o_type mesh -body_o_op intersect -body_o_file "$source_dir/examples/geometry/double_edge_notched.geo")
expect_error group_missing "-load_top_group grip: '$source_dir/examples/geometry/double_edge_notched.geo' has no physical group named 'grip' (it has 'notch_left' (curve), 'notch_right' (curve), 'grip_bottom' (surface), 'specimen' (surface), 'grip_top' (surface))" \
  "$scene" "${den[@]}" -load_top_region group -load_top_group grip
expect_error group_file_missing "-load_top_group grip_top: cannot open 'no_such.msh'" "$scene" -load_top_region group -load_top_group grip_top \
  -load_top_file no_such.msh
expect_error group_file_not_gmsh "-load_top_group grip_top: Gmsh cannot read" "$scene" -load_top_region group -load_top_group grip_top \
  -load_top_file "$source_dir/tests/data/geometry/broken.geo"
# The sheet is 10 mm x 10 mm of the 20 mm x 40 mm outline: its top tab lies beyond it.
expect_error group_selects_nothing "-load_top_group grip_top (of $source_dir/examples/geometry/double_edge_notched.geo) selects no material point for load set 'top'" \
  "$scene" "${den[@]}" -load_top_region group -load_top_group grip_top
expect_error polygon_crossing "-load_top_points (the polygon of load set 'top'): edges 1 and 3 cross" "$scene" -load_top_region polygon \
  -load_top_points 0,0.008,0.01,0.01,0.01,0.008,0,0.01
expect_error polygon_open "-load_top_points holds 4 numbers: give x,y pairs, at least 3 vertices for a polygon" "$scene" \
  -load_top_region polygon -load_top_points 0,0.01,0.01,0.01
# (between the point rows y = 9.25 and 9.75 mm)
expect_error polygon_selects_nothing "-load_top_points: the polygon selects no material point for load set 'top'" "$scene" \
  -load_top_region polygon -load_top_points 0.001,0.0093,0.009,0.0093,0.005,0.0097
expect_error curve_selects_nothing "-load_top_points: the curve selects no material point for load set 'top': raise -load_top_depth" "$scene" \
  -load_top_region curve -load_top_points 0,0.01,0.01,0.01 -load_top_depth 0.0002
expect_error group_placed_outside "-load_top_placement outside: load set 'top' is a group" "$scene" "${den[@]}" -load_top_region group \
  -load_top_group grip_bottom -load_top_placement outside
# A negative scale moves a grip against the stretch (the plate's bottom grip, -0.5): two
# opposite grips pulled together as lambda grows compress the body where the schedule
# says stretched (the tiny scene's bottom grip is fixed).
expect_error scale_compresses "-load_top_y_scale -1 (a top grip) and -load_bottom_y fixed (a bottom grip) move the two grips toward each other" \
  "$scene" -load_top_y_scale -1
expect_error scale_pushes_lower_grip "-load_top_y_scale 1 (a top grip) and -load_bottom_y_scale 2 (a bottom grip) move the two grips toward each other" \
  "$scene" -load_bottom_y stretch -load_bottom_y_scale 2
# Probes by physical point (scene_probes.cpp)
pp="$source_dir/tests/data/geometry/probe_point.geo"
ppb=(-body_shapes sq -body_sq_type mesh -body_sq_op intersect -body_sq_file "$pp" -probes p)
expect_error probe_group_curve "-probe_p_group top_edge: a probe is one point, but group 'top_edge' of '$pp' is a physical curve" \
  "$scene" "${ppb[@]}" -probe_p_group top_edge
expect_error probe_group_missing "-probe_p_group centre: '$pp' has no physical group named 'centre'" "$scene" "${ppb[@]}" -probe_p_group centre
expect_error probe_at_and_group "probe 'p' has both -probe_p_at and -probe_p_group: give one of them" "$scene" "${ppb[@]}" \
  -probe_p_group gauge -probe_p_at 0.005,0.005
# Point clouds (-body_cloud, point_cloud_file.hpp) and element centroids (geometry.hpp):
# cloud.csv is a good 20 x 20 cloud of the 10 mm sheet; each case spoils one thing.
cloud_scene="$fixtures/cloud.yaml"
write_cloud() { # write_cloud FILE [HEADER]: the good cloud, with HEADER as its first line
  awk -v header="${2:-x,y,volume,block_id}" 'BEGIN { print header
    for (j = 0; j < 20; j++) for (i = 0; i < 20; i++) printf "%.17g,%.17g,2.5e-10,1\n", (i + 0.5) * 0.0005, (j + 0.5) * 0.0005 }' > "$1"
}
write_cloud cloud.csv
write_cloud no_volume.csv "x,y,vol,block_id"
sed '3s/,2.5e-10,/,0,/' cloud.csv > zero_volume.csv
sed '5s/,2.5e-10,/,-1e-10,/' cloud.csv > negative_volume.csv
{ cat cloud.csv; sed -n 3p cloud.csv; } > duplicate.csv
awk -F, 'NR == 1 || $1 < 0.0045 || $1 > 0.0065' cloud.csv > two_pieces.csv # a 2 mm gap > delta = 1.5 mm
echo "x,y,volume" > not_hdf5.h5
expect_error cloud_missing "-body_cloud: cannot open 'no_such.csv'" "$cloud_scene" -body_cloud no_such.csv
expect_error cloud_unreadable "-body_cloud: 'not_hdf5.h5' is not an HDF5 file" "$cloud_scene" -body_cloud not_hdf5.h5
expect_error cloud_directory "-body_cloud: '.' is a directory" "$cloud_scene" -body_cloud .
# A device or a pipe would be read forever: refused before a byte is read.
expect_error cloud_device "-body_cloud: '/dev/zero' is a device" "$cloud_scene" -body_cloud /dev/zero
expect_error cloud_no_volume_column "-body_cloud: 'no_volume.csv', line 1: the header 'x,y,vol,block_id' names no column 'volume'" \
  "$cloud_scene" -body_cloud no_volume.csv
expect_error cloud_zero_volume "-body_cloud: 'zero_volume.csv', line 3 (point 2 at (0.00075, 0.00025) m): volume 0 m^3" \
  "$cloud_scene" -body_cloud zero_volume.csv
expect_error cloud_negative_volume "'negative_volume.csv', line 5 (point 4 at (0.00175, 0.00025) m): volume -1e-10 m^3" \
  "$cloud_scene" -body_cloud negative_volume.csv
expect_error cloud_duplicate "-body_cloud: 'duplicate.csv': line 3 and line 402 are the same point (0.00075, 0.00025) m" \
  "$cloud_scene" -body_cloud duplicate.csv
expect_error cloud_grip_outside "-load_top_placement outside: a grip outside the specimen extrudes the lattice's edge rows" \
  "$cloud_scene" -load_top_placement outside
expect_error cloud_with_dx "-body_dx is the lattice spacing, but -body_cloud gives the body's points" "$cloud_scene" -body_dx 0.0005
expect_error centroids_no_elements "-body_cut_file: '$source_dir/tests/data/geometry/lines_only.geo' holds no surface" "$scene" "${sh[@]}" \
  -body_cut_type mesh -body_cut_file "$source_dir/tests/data/geometry/lines_only.geo" -body_cut_discretisation centroids
expect_error centroids_not_mesh "-body_cut_discretisation centroids: only a mesh shape" "$scene" "${sh[@]}" -body_cut_type circle \
  -body_cut_centre 0.005,0.005 -body_cut_radius 0.002 -body_cut_discretisation centroids
expect_error cloud_two_pieces "two_pieces.csv: the given points fall apart into 2 pieces with no bond between them (the smallest: 140 point(s)" \
  "$cloud_scene" -body_cloud two_pieces.csv
# Block ids as load sets (-load_S_region block): an id no point has (the ids there are
# listed), and a lattice body, which has no block ids.
expect_error cloud_block_missing "-load_top_block 7: no point of 'cloud.csv' has block id 7 (its block ids: 1): give one of them" \
  "$cloud_scene" -load_top_region block -load_top_block 7
expect_error block_on_lattice "-load_top_region block: block ids come with the points of a cloud" "$scene" -load_top_region block \
  -load_top_block 1
expect_error probe_block_many "-probe_p_block 1: a probe is one point, but block 1 has 400 points" "$cloud_scene" -probes p -probe_p_block 1
# The affine field for two region grips needs one wholly above the other.
expect_error region_grips_overlap "-load_grip_field affine: load sets 'bottom' and 'top' overlap in y" "$scene" -load_grip_field affine \
  -load_top_region box -load_top_box 0,0.004,0.01,0.01 -load_bottom_region box -load_bottom_box 0,0,0.01,0.006
# A cloud that needs more memory than the machine has (here by a huge horizon, so that
# the file stays small): the fix names the cloud and the horizon, not -body_dx.
expect_error cloud_needs_more_memory "-body_cloud 'cloud.csv' gives 400 material points" "$cloud_scene" -horizon_factor 3000

# -force_patch_correction (patch_correction.hpp): a word that is not a choice, and on or
# virial with the energy-consistent form, which neither corrects.
expect_error patch_correction_word "-force_patch_correction 'maybe' is not a choice" "$cloud_scene" -force_patch_correction maybe
expect_error patch_correction_energy "-force_patch_correction on corrects the bond-only force only" "$cloud_scene" \
  -force_form energy_consistent -force_patch_correction on
expect_error patch_correction_energy_virial "-force_patch_correction virial corrects the bond-only force only" "$cloud_scene" \
  -force_form energy_consistent -force_patch_correction virial

# Options are checked before any work (docs/options.md): a typo or a bad -ts_* value
# stops the run before the scene is shown and the body is built.
for name in unknown_option nested_optional_key petsc_real petsc_int petsc_ts_type; do
  if [ -f "$name.log" ] && grep -qE "^(Scene$|Body: [0-9])" "$name.log"; then
    echo "FAIL $name: reported only after the body was built"
    failures=$((failures + 1))
  fi
done

if ((cases == 0)); then
  echo "FAIL: no case belongs to part '$only' (give options, geometry, sets or all)"
  exit 1
fi
if ((failures)); then
  echo "$failures of $cases case(s) failed"
  exit 1
fi
echo "every bad input ($only, $cases cases$( ((ranks == 1)) || echo ", the parallel sample")) was refused cleanly on $ranks rank(s)"
