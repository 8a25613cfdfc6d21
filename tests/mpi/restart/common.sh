# Shared by the restart tests (sourced): the scene and a runner.
#
# A notched sheet pulled apart, as in tests/mpi/rank_invariance.sh: plane-stress
# Gent, 60 x 24 points, coarse enough to run in seconds. With -failure_critical_stretch
# 2.0 and the ramp to 1.6 over 0.2 s the first bonds break near step 400 and the crack
# runs across the sheet between steps 600 and 800.
NOTCHED=(-body_width 0.03 -body_height 0.012 -body_thickness 0.003 -body_dx 0.0005
         -body_notches 0.02,0.006,0.03,0.006 -horizon_factor 3.015
         -material_mu 4.55e3 -material_Jm 162.6 -material_bulk_ratio 100 -material_density 1000
         -load_sets top,bottom -load_top_region top -load_top_x fixed -load_top_y stretch -load_top_y_scale 1
         -load_bottom_region bottom -load_bottom_x fixed -load_bottom_y fixed
         -probes mouth -probe_mouth_at 0.03,0.0062 -damping 40 -output_interval 50 -progress_interval 100000
         -output_final_state)
# (-time_step_travel: the steps shorten while the crack runs, so the restart must carry dt)
FRACTURE=(-load_schedule 0,1,0.2,1.6 -failure_critical_stretch 2.0 -time_step_travel 0.1)

# h5py, numpy and matplotlib are Debian's (scripts/install-deps.sh).
PYTHON=/usr/bin/python3

# run RANKS DIR OPTIONS...: bapd on RANKS ranks writing to DIR (log in DIR.log);
# prints the log and fails the test if bapd fails.
run() {
  local ranks="$1" dir="$2"
  shift 2
  mpiexec -n "$ranks" --oversubscribe --bind-to none "$BAPD_EXE" "$@" -output_dir "$dir" > "$dir.log" 2>&1 ||
    { cat "$dir.log"; echo "FAILED: bapd on $ranks rank(s) -> $dir"; exit 1; }
}

# checkpointed_runs WORK N END OPTIONS...: on 2 ranks the run of END steps (WORK/whole)
# and the run stopped at step N with a checkpoint (WORK/first); then its continuations
# with -restart on 2 and 3 ranks to step END (WORK/second_np2, WORK/second_np3), checked
# to restart at N.
checkpointed_runs() {
  local work="$1" N="$2" end="$3"
  shift 3
  run 2 "$work/whole" "$@" -end_step $end
  run 2 "$work/first" "$@" -end_step $N -checkpoint_interval $N
  [ -f "$work/first/checkpoint.h5" ] || fail "no checkpoint after $N steps"
  # The scene comes from the checkpoint: only the run length and the output change.
  run 2 "$work/second_np2" -restart "$work/first/checkpoint.h5" -end_step $end
  run 3 "$work/second_np3" -restart "$work/first/checkpoint.h5" -end_step $end
  grep -q "Restart from $work/first/checkpoint.h5: step $N" "$work/second_np3.log" || fail "no restart line in second_np3.log"
}

# same_as_whole WORK END [--expect-broken] [--fields]: the continuations on 2 and 3 ranks
# (checkpointed_runs) give the uninterrupted run's history and final state (and its
# broken bonds: --expect-broken), tolerance 0; with --fields also its last field file.
same_as_whole() {
  local work="$1" end="$2" expect="" fields=0 d a
  shift 2
  for a in "$@"; do case "$a" in --expect-broken) expect="$a" ;; --fields) fields=1 ;; esac; done
  local last
  last=$(printf "fields/step_%08d.h5" "$end")
  for d in second_np2 second_np3; do
    python3 "$BAPD_SOURCE_DIR/tests/mpi/compare_runs.py" --tolerance 0 $expect "$work/whole" "$work/$d"
    [ $fields = 0 ] || $PYTHON "$BAPD_SOURCE_DIR/tests/mpi/restart/compare_fields.py" --tolerance 0 "$work/whole/$last" "$work/$d/$last"
  done
}

# crack_grows WORK N END: the uninterrupted run has broken bonds at step N and more at END,
# so the restart met a crack that runs on.
crack_grows() {
  local at_n at_end
  at_n=$(history_column "$1/whole" "$2" broken_bonds)
  at_end=$(history_column "$1/whole" "$3" broken_bonds)
  echo "broken bonds: $at_n at step $2, $at_end at step $3"
  [ "$at_n" -gt 0 ] && [ "$at_end" -gt "$at_n" ] || fail "the crack must grow both before and after the restart"
}

# history_column DIR STEP COLUMN: a value of history.csv's row for STEP.
history_column() {
  awk -F, -v step="$2" -v name="$3" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == name) c = i }
                                      NR > 1 && $1 == step { print $c }' "$1/history.csv"
}

fail() { echo "FAILED: $*"; exit 1; }

# side_by_side FUNCTION...: the functions at once, each in a process of its own (a test
# that holds two cores keeps both busy); a function that fails prints why, and the test
# fails once every one has ended.
side_by_side() {
  local part pid status=0 pids=()
  for part in "$@"; do
    "$part" &
    pids+=($!)
  done
  for pid in "${pids[@]}"; do wait "$pid" || status=1; done
  ((status == 0)) || fail "a part above failed"
}
