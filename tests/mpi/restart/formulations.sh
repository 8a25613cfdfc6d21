#!/usr/bin/env bash
# The nearly incompressible formulations across a restart: a run of END steps, and the
# same run stopped at step N with a checkpoint and continued with -restart on 2 and on 3
# ranks, give the same history, final displacements and last field file, tolerance 0
# (checkpointed_runs, common.sh).
#   formulations.sh volumetric_point     plane strain at K = 1000 mu with -material_volumetric
#                                        point: each point's mean dilatation is formed again
#                                        from the restored positions, nothing of it is stored
#   formulations.sh volumetric_point_3d  the same in 3D, a small box pulled along x
#   formulations.sh incompressible       the notched sheet cracking in
#                                        -material_formulation plane_stress_incompressible
#                                        (C33 = 1/det C~ a bond: no warm start to store)
set -euo pipefail
source "$BAPD_SOURCE_DIR/tests/mpi/restart/common.sh"
case="$1"
work="restart_formulations_$case"
rm -rf "$work"; mkdir -p "$work"
if [ "$case" = volumetric_point ]; then
  # 30 x 12 points, no failure, pulled fast (stretch 1.12 at step N, 1.23 at END): the
  # short step of K = 1000 mu in plane strain (2.6e-5 s) makes a slow pull a few
  # micrometres in 300 steps.
  scene=("${NOTCHED[@]}" -body_dx 0.001 -material_formulation plane_strain -material_bulk_ratio 1000
         -material_volumetric point -load_schedule 0,1,0.01,1.3)
  said="volumetric energy per point"
  N=150 END=300
elif [ "$case" = volumetric_point_3d ]; then
  # 8 x 4 x 4 cells of 1 mm (128 points), held on x-, pulled on x+.
  scene=(-body_dimension 3 -body_dx 0.001 -body_shapes block -body_block_type box -body_block_box 0,0,0,0.008,0.004,0.004
         -horizon_factor 3.015 -material_mu 4.55e3 -material_Jm 162.6 -material_bulk_ratio 1000 -material_density 1000
         -material_volumetric point
         -load_sets left,right -load_left_region x- -load_left_x fixed -load_left_y fixed -load_left_z fixed
         -load_right_region x+ -load_right_x stretch -load_right_y fixed -load_right_z fixed -load_reference_length 0.008
         -probes p -probe_p_at 0.0065,0.0025,0.0025 -damping 40 -output_interval 20 -progress_interval 100000
         -output_final_state -load_schedule 0,1,0.01,1.2)
  said="volumetric energy per point"
  N=150 END=300
else
  # 30 x 12 points (as restart.fields): bonds break from step 195, 3 by step N, 12 by END.
  scene=("${NOTCHED[@]}" "${FRACTURE[@]}" -body_dx 0.001 -material_formulation plane_stress_incompressible)
  said="plane_stress_incompressible"
  N=225 END=300
fi
scene+=(-output_fields -output_fields_interval $((END / 2)))
checkpointed_runs "$work" $N $END "${scene[@]}"
# The formulation comes back from the checkpoint's options (the restarts name none).
for d in second_np2 second_np3; do grep -q "$said" "$work/$d.log" || fail "$d did not run with $said"; done
if [ "$case" = incompressible ]; then
  same_as_whole "$work" $END --expect-broken --fields
  crack_grows "$work" $N $END
else
  same_as_whole "$work" $END --fields
fi
echo "restart ($case): same results"
