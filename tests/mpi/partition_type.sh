#!/usr/bin/env bash
# -partition_type: the same scene split by METIS on rank 0 and by PT-Scotch on every
# rank (a lattice body built in slabs, one a rank), on 1 to 3 ranks: the same history,
# final displacements and broken bonds, tolerance 0 (the results do not depend on the
# partition: every sum runs in natural order).
#   partition_type.sh sheet    a 2D sheet (a hole; the grips extrude rows outside it), pulled
#   partition_type.sh box      a 3D box with a cylinder cut out, pulled
#   partition_type.sh notched  the notched 2D sheet of rank_invariance.sh, bonds breaking
#   partition_type.sh cloud    given points: built on rank 0 (said so), cut by PT-Scotch
#   partition_type.sh refused  -partition_type other: one clear error
set -euo pipefail
case="$1"
work="partition_type_$case"
rm -rf "$work"; mkdir -p "$work"
fail() { echo "partition_type.sh $case: $*" >&2; exit 1; }
run() { # run NAME RANKS PARTITIONER ARGS...
  local name=$1 n=$2 type=$3; shift 3
  mpiexec -n "$n" --oversubscribe --bind-to none "$BAPD_EXE" "$@" -partition_type "$type" -output_dir "$work/$name" \
    > "$work/$name.log" 2>&1 || { cat "$work/$name.log"; fail "$name failed"; }
}
GENT=(-material_mu 4.55e3 -material_Jm 162.6 -material_density 1000 -damping 40 -progress_interval 100000 -output_final_state)
case "$case" in
sheet)
  scene=(-body_width 0.02 -body_height 0.012 -body_thickness 0.002 -body_dx 0.0005 -horizon_factor 3.015
         -body_holes 0.012,0.005,0.002 -material_bulk_ratio 100 "${GENT[@]}"
         -load_sets top,bottom -load_top_region top -load_top_x fixed -load_top_y stretch
         -load_bottom_region bottom -load_bottom_x fixed -load_bottom_y fixed
         -load_schedule 0,1,0.1,1.3 -end_step 150 -output_interval 50) ;;
box)
  scene=(-body_dimension 3 -body_dx 0.001 -body_shapes block,bore -body_block_type box -body_block_box 0,0,0,0.010,0.006,0.005
         -body_bore_type cylinder -body_bore_op subtract -body_bore_axis 0.005,0.003,0,0.005,0.003,0.005 -body_bore_radius 0.0015
         -horizon_factor 3.015 -material_bulk_ratio 10 "${GENT[@]}"
         -load_sets left,right -load_left_region x- -load_left_x fixed -load_left_y fixed -load_left_z fixed
         -load_right_region x+ -load_right_x stretch -load_right_y fixed -load_right_z fixed -load_reference_length 0.010
         -load_schedule 0,1,0.1,1.2 -end_step 100 -output_interval 20) ;;
notched)
  scene=(-body_width 0.03 -body_height 0.012 -body_thickness 0.003 -body_dx 0.0005 -body_notches 0.02,0.006,0.03,0.006
         -horizon_factor 3.015 -material_bulk_ratio 100 "${GENT[@]}"
         -load_sets top,bottom -load_top_region top -load_top_x fixed -load_top_y stretch
         -load_bottom_region bottom -load_bottom_x fixed -load_bottom_y fixed
         -load_schedule 0,1,0.15,1.45 -failure_critical_stretch 2.0 -end_step 400 -output_interval 50) ;;
cloud)
  scene=(-options_file_yaml "$BAPD_SOURCE_DIR/examples/point_cloud.yaml"
         -body_cloud "$BAPD_SOURCE_DIR/examples/geometry/graded_sheet.csv"
         -load_schedule 0,1,0.05,1.2 -end_step 100 -output_interval 50 -progress_interval 100000 -output_final_state) ;;
refused)
  if "$BAPD_EXE" -partition_type parmetis -body_width 0.01 -body_height 0.01 -body_thickness 0.001 -body_dx 0.001 \
       -output_dir "$work/out" > "$work/log" 2>&1; then
    fail "-partition_type parmetis was accepted"
  fi
  grep -q "bapd: error: -partition_type 'parmetis' is not a partitioner: choose metis (the default) or ptscotch" "$work/log" ||
    { cat "$work/log"; fail "no clear error for -partition_type parmetis"; }
  echo "-partition_type parmetis refused: $(grep 'bapd: error' "$work/log")"
  exit 0 ;;
*) fail "no case '$case'" ;;
esac
run metis_np1 1 metis "${scene[@]}"
runs=("$work/metis_np1")
ranks=(1 2 3)
[ "$case" = notched ] && ranks=(1 3) # a running crack: five force evaluations a step
for n in "${ranks[@]}"; do
  [ "$n" = 1 ] || { run "metis_np$n" "$n" metis "${scene[@]}"; runs+=("$work/metis_np$n"); }
  run "ptscotch_np$n" "$n" ptscotch "${scene[@]}"; runs+=("$work/ptscotch_np$n")
done
# The lattice is set up on every rank, given points on rank 0, and the log says which.
for n in "${ranks[@]}"; do
  if [ "$case" = cloud ]; then
    grep -q "Set-up: the given points built on rank 0" "$work/ptscotch_np$n.log" || fail "ptscotch_np$n: no word that the points were built on rank 0"
  else
    ! grep -q "built on rank 0" "$work/ptscotch_np$n.log" || fail "ptscotch_np$n: the lattice was built on rank 0"
  fi
  grep "^Body:" "$work/ptscotch_np$n.log"
done
# The same body: its points and bonds as METIS's run counts them.
body() { grep "^Body:" "$1.log" | sed 's/ *[0-9]* rank(s).*//'; }
for r in "${runs[@]:1}"; do
  [ "$(body "$r")" = "$(body "${runs[0]}")" ] || fail "$(basename "$r"): $(body "$r"), not $(body "${runs[0]}")"
done
python3 "$BAPD_SOURCE_DIR/tests/mpi/compare_runs.py" --tolerance 0 $([ "$case" = notched ] && echo --expect-broken) "${runs[@]}"
