#!/usr/bin/env bash
# A run of END steps, and the same run stopped at step N with a checkpoint and
# continued with -restart, give the same history, final displacements, broken bonds
# and field files: bit for bit on the same number of ranks, and on another one
# (checkpoint on 2 ranks, restart on 3: the results never depend on the layout, so
# they agree bit for bit there too, tolerance 0).
#   continuation.sh fracture      the crack starts before step N and runs after it
#   continuation.sh fracture_energy  the same by -failure_fracture_energy (its pair
#                                 energies are recomputed from the state, not checkpointed)
#   continuation.sh static_hold   a hold ends early (-static_tolerance) before step N
#                                 and another after it: the moved schedule goes on
#   continuation.sh cloud         the graded point cloud of examples/point_cloud.yaml
#                                 with the bond-only form and the default patch
#                                 correction (virial): its per-point numbers are solved
#                                 again at the restart, not checkpointed
set -euo pipefail
source "$BAPD_SOURCE_DIR/tests/mpi/restart/common.sh"
case="$1"
work="restart_continuation_$case"
rm -rf "$work"; mkdir -p "$work"
if [ "$case" = fracture ]; then
  # Bonds break from step 300, 16 by step 450 and 186 by step 600 (the crack runs on
  # across the sheet until step 1200, which adds nothing the restart has not met).
  scene=("${NOTCHED[@]}" "${FRACTURE[@]}" -output_fields -output_fields_interval 150)
  N=450 END=600
elif [ "$case" = fracture_energy ]; then
  # Bonds break from step 466, 22 by step 500 and 67 by step 600 (215 by step 750,
  # which adds crack-tip searches, not a case the restart has not met).
  scene=("${NOTCHED[@]}" -load_schedule 0,1,0.2,1.6 -failure_fracture_energy 6 -time_step_travel 0.1
         -output_fields -output_fields_interval 150)
  N=500 END=600
elif [ "$case" = cloud ]; then
  scene=(-options_file_yaml "$BAPD_SOURCE_DIR/examples/point_cloud.yaml"
         -body_cloud "$BAPD_SOURCE_DIR/examples/geometry/graded_sheet.csv" -force_form bond_only
         -load_schedule 0,1,0.05,1.2 -output_interval 25 -progress_interval 100000 -output_final_state)
  N=100 END=200
else
  # 30 x 12 points, no failure: holds at stretch 1.2 and 1.3 that end once static
  # (steps 140 and 280); the run ends with the schedule, before END.
  scene=("${NOTCHED[@]}" -body_dx 0.001 -load_schedule 0,1,0.05,1.2,1.0,1.2,1.05,1.3,2.0,1.3
         -static_tolerance 1e-3 -output_interval 10)
  N=200 END=400
fi
checkpointed_runs "$work" $N $END "${scene[@]}"

if [ "$case" = fracture ] || [ "$case" = fracture_energy ]; then
  same_as_whole "$work" $END --expect-broken --fields
  crack_grows "$work" $N $END
elif [ "$case" = cloud ]; then
  same_as_whole "$work" $END
  grep -q "^Patch correction virial" "$work/second_np3.log" || fail "the restart did not solve the virial patch correction"
else
  same_as_whole "$work" $END
  [ "$(grep -c '^Static at' "$work/first.log")" = 1 ] || fail "expected one hold to end before step $N"
  [ "$(grep -c '^Static at' "$work/second_np3.log")" = 1 ] || fail "expected one hold to end after step $N"
  for d in second_np2 second_np3; do
    cmp "$work/whole/static_states.csv" "$work/$d/static_states.csv" || fail "$d/static_states.csv differs"
  done
fi
echo "restart continuation ($case): same results"
