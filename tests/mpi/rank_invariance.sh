#!/usr/bin/env bash
# The same scene on 1, 2, 3 and 4 ranks: the same history, final displacement field
# (bit for bit: tolerance 0) and set of broken bonds.
#   rank_invariance.sh elastic|fracture|fracture_corrected
# (fracture_corrected: fracture with -force_stress_correction tensor, whose per-point
# correction is rebuilt on every rank, ghosts included, as bonds break)
set -euo pipefail
case="$1"
work="rank_invariance_$case"
rm -rf "$work"; mkdir -p "$work"
# A notched sheet pulled apart: plane-stress Gent, coarse enough to run in seconds.
scene=(-body_width 0.03 -body_height 0.012 -body_thickness 0.003 -body_dx 0.0005
       -body_notches 0.02,0.006,0.03,0.006 -horizon_factor 3.015
       -material_mu 4.55e3 -material_Jm 162.6 -material_bulk_ratio 100 -material_density 1000
       -load_sets top,bottom -load_top_region top -load_top_x fixed -load_top_y stretch -load_top_y_scale 1
       -load_bottom_region bottom -load_bottom_x fixed -load_bottom_y fixed
       -probes mouth -probe_mouth_at 0.03,0.0062 -damping 40 -output_interval 50 -progress_interval 100000
       -output_final_state)
if [ "$case" = fracture ] || [ "$case" = fracture_corrected ]; then
  # Stretch the sheet fast enough that the notch opens and bonds break within the run.
  scene+=(-load_schedule 0,1,0.2,1.6 -failure_critical_stretch 2.0)
  [ "$case" = fracture_corrected ] && scene+=(-force_stress_correction tensor)
else
  scene+=(-load_schedule 0,1,0.1,1.3)
fi
for n in 1 2 3 4; do
  mpiexec -n $n --oversubscribe --bind-to none "$BAPD_EXE" "${scene[@]}" -output_dir "$work/np$n" > "$work/np$n.log" 2>&1 ||
    { cat "$work/np$n.log"; exit 1; }
done
python3 "$BAPD_SOURCE_DIR/tests/mpi/compare_runs.py" --tolerance 0 $([ "$case" != elastic ] && echo --expect-broken) \
  "$work/np1" "$work/np2" "$work/np3" "$work/np4"
