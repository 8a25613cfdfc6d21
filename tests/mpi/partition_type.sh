#!/usr/bin/env bash
# -partition_type: the same scene split by METIS on rank 0 and by PT-Scotch on every
# rank (a lattice body built in slabs, one a rank; given points' families built in
# slabs along x, each with the points within the largest horizon), on 1 to 3 ranks: the same history,
# final displacements and broken bonds, tolerance 0 (the results do not depend on the
# partition: every sum runs in natural order).
#   partition_type.sh sheet    a 2D sheet (a hole; the grips extrude rows outside it), pulled
#   partition_type.sh box      a 3D box with a cylinder cut out, pulled
#   partition_type.sh notched  the notched 2D sheet of rank_invariance.sh, bonds breaking
#   partition_type.sh cloud    given 2D points (a graded CSV cloud): set up on every rank
#   partition_type.sh cloud3d  given 3D points (a jittered cloud: per-point horizons of every size)
#   partition_type.sh pieces   given 2D points in two pieces: the same one error with either
#   partition_type.sh refused  -partition_type other: one clear error
set -euo pipefail
PYTHON=${PYTHON:-/usr/bin/python3}
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
cloud3d)
  # a jittered block (1 mm cells, positions +-0.2 mm, volumes +-20 %: per-point
  # horizons of every size), block 2 its first column, block 3 its last
  $PYTHON - "$work/jittered.txt" <<'PY'
import random, sys
random.seed(7)
nx, ny, nz, h = 12, 6, 4, 1e-3
with open(sys.argv[1], "w") as f:
    f.write("x y z volume block_id\n")
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                at = [(c + 0.5 + random.uniform(-0.2, 0.2)) * h for c in (i, j, k)]
                block = 2 if i == 0 else 3 if i == nx - 1 else 1
                f.write("%.17g %.17g %.17g %.17g %d\n" % (*at, h ** 3 * random.uniform(0.8, 1.2), block))
PY
  scene=(-body_dimension 3 -body_cloud "$work/jittered.txt" -horizon_factor 3.015 -material_bulk_ratio 10 "${GENT[@]}"
         -load_sets left,right -load_left_region block -load_left_block 2 -load_left_x fixed -load_left_y fixed -load_left_z fixed
         -load_right_region block -load_right_block 3 -load_right_x stretch -load_right_y fixed -load_right_z fixed
         -load_reference_length 0.011
         -load_schedule 0,1,0.1,1.2 -end_step 100 -output_interval 20) ;;
pieces)
  # Two 2D patches 5 mm apart (further than any horizon): rank 0 and the slabs must
  # refuse them with one and the same message, the smaller patch's first point named.
  $PYTHON - "$work/pieces.csv" <<'PY'
import sys
with open(sys.argv[1], "w") as f:
    f.write("x,y,volume\n")
    for x0, nx in ((0.0, 12), (0.017, 3)):
        for j in range(6):
            for i in range(nx):
                f.write("%.17g,%.17g,%.17g\n" % (x0 + (i + 0.5) * 1e-3, (j + 0.5) * 1e-3, 1e-6 * 1e-3))
PY
  for type in metis ptscotch; do
    for n in 1 3; do
      if OMPI_MCA_odls_base_sigkill_timeout=0 mpiexec -n $n --oversubscribe --bind-to none "$BAPD_EXE" -body_cloud "$work/pieces.csv" -body_thickness 0.001 \
           -horizon_factor 3.015 "${GENT[@]}" -end_step 1 -end_time 1 -partition_type $type -output_dir "$work/out" > "$work/$type$n.log" 2>&1; then
        fail "$type on $n rank(s): two pieces were accepted"
      fi
      [ "$(grep -c 'bapd: error' "$work/$type$n.log")" = 1 ] || { cat "$work/$type$n.log"; fail "$type on $n rank(s): not one error line"; }
    done
  done
  want="the given points fall apart into 2 pieces with no bond between them (the smallest: 18 point(s), e.g. point 72 at (0.0175, 0.0005) m)"
  grep -qF "$want" "$work/metis1.log" || { cat "$work/metis1.log"; fail "not the expected message"; }
  for log in metis3 ptscotch1 ptscotch3; do
    diff <(grep 'bapd: error' "$work/metis1.log") <(grep 'bapd: error' "$work/$log.log") || fail "$log: another message than rank 0's"
  done
  echo "pieces refused alike: $(grep 'bapd: error' "$work/metis1.log")"
  exit 0 ;;
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
# The lattice and given points are set up on every rank: no word of rank 0.
for n in "${ranks[@]}"; do
  ! grep -q "built on rank 0" "$work/ptscotch_np$n.log" || fail "ptscotch_np$n: the body was built on rank 0"
  grep "^Body:" "$work/ptscotch_np$n.log"
done
# The same body: its points and bonds as METIS's run counts them.
body() { grep "^Body:" "$1.log" | sed 's/ *[0-9]* rank(s).*//'; }
for r in "${runs[@]:1}"; do
  [ "$(body "$r")" = "$(body "${runs[0]}")" ] || fail "$(basename "$r"): $(body "$r"), not $(body "${runs[0]}")"
done
python3 "$BAPD_SOURCE_DIR/tests/mpi/compare_runs.py" --tolerance 0 $([ "$case" = notched ] && echo --expect-broken) "${runs[@]}"
