# The scenes of full_disk.sh (sourced, with $what set): scene, the tmpfs size kb and
# the file whose write fails. The tiny scene keeps the paper's one-row grips inside
# it, so that its files have the sizes below (400 points; the default grips outside
# add 240 points and every file grows by 1.6 x).
tiny=("$TINY" -load_grip_placement inside)
case "$what" in
  checkpoint) # checkpoint 114 KB (150 KB reserved): the one of step 10 fits, the next not
    kb=250 scene=("${tiny[@]}" -checkpoint_interval 10 -output_interval 2) file=checkpoint.h5 ;;
  fields) # field files of 164 KB (196 KB reserved): steps 0 and 2 fit, step 4 not
    kb=400 scene=("${tiny[@]}" -output_fields -output_fields_interval 2 -output_interval 2) file=fields/step_ ;;
  checkpoint_late | fields_late) # no reservation (BAPD_TEST_NO_SPACE_RESERVATION): the
    # writes fail inside HDF5, as on a disk another program fills after the reservation
    export BAPD_TEST_NO_SPACE_RESERVATION=1
    if [ "$what" = checkpoint_late ]; then # 180 KB: the second checkpoint's /bonds fail
      kb=180 scene=("${tiny[@]}" -checkpoint_interval 10 -output_interval 2) file=checkpoint.h5
    else # 400 KB: the third field file fails
      kb=400 scene=("${tiny[@]}" -output_fields -output_fields_interval 2 -output_interval 2) file=fields/step_
    fi ;;
  final_state) # 8 KB free (full_disk.sh): history.csv's rows (every 10 steps, none by load) fit, final_state.csv (about 30 KB) not
    kb=64 scene=("${tiny[@]}" -output_interval 10 -output_history_rows 0 -output_final_state) file=final_state.csv ;;
  history) # 4 KB free: about 20 rows of history.csv
    kb=64 scene=("${tiny[@]}" -output_interval 1) file=history.csv ;;
  static) # the first hold ends at step 140; full_disk.sh leaves room for history.csv
          # up to then and not for static_states.csv
    kb=64
    scene=(-body_width 0.03 -body_height 0.012 -body_thickness 0.003 -body_dx 0.001 -body_notches 0.02,0.006,0.03,0.006
           -horizon_factor 3.015 -material_mu 4.55e3 -material_Jm 162.6 -material_bulk_ratio 100 -material_density 1000
           -load_sets top,bottom -load_top_region top -load_top_x fixed -load_top_y stretch -load_bottom_region bottom
           -load_bottom_x fixed -load_bottom_y fixed -probes mouth -probe_mouth_at 0.03,0.0062 -damping 40
           -load_schedule 0,1,0.05,1.2,1.0,1.2 -static_tolerance 1e-3 -output_interval 10 -end_step 160)
    file=static_states.csv ;;
  *) echo "usage: full_disk.sh checkpoint|fields|checkpoint_late|fields_late|history|static|final_state RANKS"; exit 2 ;;
esac
