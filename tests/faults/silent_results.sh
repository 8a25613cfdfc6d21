#!/usr/bin/env bash
# Runs that used to end with exit 0 and a wrong answer: each must now stop with one
# `bapd: error:` line naming the cause and the option that fixes it, a non-zero exit,
# no hang and no crash, and the history rows already written intact (the same bytes as
# an undisturbed run's); or, for the shallow grips, run with a warning.
#   silent_results.sh RANKS CASE   (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
# CASE:
#   time_step     a -time_step or -ts_dt far above the stable step (one step of 1 s ran
#                 to "Finished" with 1.6e11 J of internal energy): refused before the first step
#   ts_type       an implicit -ts_type (beuler: step 1 never ended): refused before the first step
#   ts_limits     -ts_max_steps short of the end time ("Finished", exit 0): an error after
#                 the normal end's output; -ts_max_time: refused; -end_step: the deliberate stop, exit 0
#   chain_limit   a load past the Gent chain limit (the plate at stretch 20: exit 0, J = 2.1 to 5.5):
#                 stopped where a bond's I1 reaches it, naming -material_Jm
#   shallow_grip  grips shallower than a horizon (7.7 % off in pure shear): a warning naming -load_<set>_layers
source "$BAPD_SOURCE_DIR/tests/faults/common.sh"
ranks="$1"
what="$2"
work="faults_silent_${what}_np$ranks"
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
((ranks == 1)) && export OMPI_MCA_odls_base_sigkill_timeout=0 # (bad_input.sh explains)

# refused NAME KEY... (ARGS in `args`): stopped cleanly before the first step (no
# progress, no history row past step 0), the error line holding every KEY.
refused() {
  local name="$1"
  shift
  bounded "$name.log" "$ranks" "${args[@]}" -output_dir "$name"
  stopped_cleanly "$@"
  ! grep -qE "^(Finished|Stopped)" "$log" || fail "$name: the run took steps before it was refused"
  ok "$name"
}

# finished NAME ARGS...: the run ends with exit 0 and "Finished".
finished() {
  local name="$1"
  shift
  bounded "$name.log" "$ranks" "$@" -output_dir "$name"
  ((STATUS == 0)) || fail "$name: exit status $STATUS, want 0"
  grep -q "^Finished" "$log" || fail "$name: the run did not finish"
  ! grep -q "bapd: error:" "$log" || fail "$name: an error line"
}

case "$what" in
time_step)
  # tiny.yaml: stable step 2.75e-4 s.
  args=("$TINY" -time_step 1)
  refused time_step "-time_step 1 s is" "stable time step" "0.8 x stable" "leave -time_step out" "-time_step_allow_unstable"
  args=("$TINY" -ts_dt 1)
  refused ts_dt "-ts_dt 1 s is" "stable time step" "remove -ts_dt" "-time_step_allow_unstable"
  # The fracture scene of the report (6572 bonds broke there with exit 0), coarse.
  args=("$BAPD_SOURCE_DIR/examples/notched_pure_shear.yaml" -body_dx 0.002 -time_step 1 -end_time 0.02)
  refused notched "-time_step 1 s is" "stable time step"
  # No false alarm: a step below the stable one, and one just above it within the
  # documented 5 % margin (a warning), run to the end. (-time_step_allow_unstable,
  # which runs a longer one: divergence.sh, unstable_time_step.)
  finished below "$TINY" -time_step 2.5e-4
  finished margin "$TINY" -time_step 2.85e-4
  grep -q "WARNING: -time_step" "$log" || fail "margin: no warning for a step above the stable one"
  ;;
ts_type)
  for type in beuler theta cn bdf; do
    args=("$TINY" -ts_type "$type")
    refused "$type" "-ts_type $type is not supported" "explicit" "basicsymplectic" "rk, euler or ssp"
  done
  finished rk "$TINY" -ts_type rk
  finished ssp "$TINY" -ts_type ssp
  ;;
ts_limits)
  finished whole "$TINY"
  whole_rows whole/history.csv
  # -ts_max_steps 10 of 49: the error after what a normal end writes (the last row).
  bounded max_steps.log "$ranks" "$TINY" -ts_max_steps 17 -output_dir max_steps
  stopped_cleanly "-ts_max_steps 17" "short of its end time" "Remove -ts_max_steps" "-end_time" "-end_step"
  stopped_saying "stopped at step 17 "
  grep -q "^Stopped (see the error below): 17 steps" "$log" || fail "max_steps: the summary does not say the run stopped"
  whole_rows max_steps/history.csv
  [ "$(tail -n 1 max_steps/history.csv | cut -d, -f1)" = 17 ] || fail "max_steps: history.csv does not end at step 17"
  # (rows 0, 10: the undisturbed run's; 17 is the normal end's extra row)
  head -n 3 max_steps/history.csv > max_steps/rows_before.csv
  same_prefix max_steps/rows_before.csv whole/history.csv
  ok max_steps
  args=("$TINY" -ts_max_time 0.005)
  refused max_time "-ts_max_time is not read" "-end_time"
  # The deliberate stop: exit 0, the same rows.
  finished end_step "$TINY" -end_step 17
  grep -q "Stopped after step 17 (-end_step)" "$log" || fail "end_step: no note of the stop"
  cmp -s end_step/history.csv max_steps/history.csv || fail "end_step: history.csv differs from the -ts_max_steps run's"
  echo "ok   end_step: exit 0, $(grep "Stopped after" "$log")"
  ;;
chain_limit)
  # tiny.yaml with Jm = 10 pulled to stretch 5: its edge bonds reach I1 - 3 = Jm near
  # stretch 3.2, where the plane-stress sheet would go on only by swelling (J > 1).
  limit=("$TINY" -material_Jm 10 -load_schedule 0,1,0.02,5 -output_interval 5)
  bounded limit.log "$ranks" "${limit[@]}" -output_dir limit
  stopped_cleanly "-material_Jm" "chain limit" "Cause: the Gent chain limit" "reference position" "volume ratio J" "Raise -material_Jm (now 10)"
  stopped_saying "at step [0-9]+ \(t = "
  whole_rows limit/history.csv
  step=$(grep 'bapd: error:' "$log" | sed -nE 's/.* at step ([0-9]+) .*/\1/p')
  [ -n "$step" ] || fail "limit: no step in the error line"
  [ -f limit/checkpoint.h5 ] || fail "limit: no checkpoint of the last good state"
  ok limit
  # The rows before the stop: those of the same run stopped on purpose one step earlier.
  bounded before.log "$ranks" "${limit[@]}" -end_step $((step - 1)) -output_dir before
  ((STATUS == 0)) || fail "before: exit status $STATUS"
  same_prefix limit/history.csv before/history.csv
  echo "ok   before: the $(($(wc -l < limit/history.csv) - 1)) rows written before the stop are those of the run stopped at step $((step - 1))"
  # The plate of the report (stretch 20, the paper's Jm 162.6), coarse.
  if ((ranks == 2)); then
    bounded plate.log "$ranks" "$BAPD_SOURCE_DIR/examples/plate_hole.yaml" -body_dx 0.004 -load_schedule 0,1,0.5,20 -end_time 0.5 \
      -output_interval 10 -progress_interval 100000 -output_dir plate
    stopped_cleanly "-material_Jm 162.6" "Cause: the Gent chain limit"
    whole_rows plate/history.csv
    ok plate
  fi
  # No false alarm: the same sheet with the paper's Jm to stretch 3.
  finished valid "$TINY" -load_schedule 0,1,0.02,3
  ;;
shallow_grip)
  warning="grips 1 row(s), 0.0005 m deep, less than the horizon"
  finished shallow "$TINY" -load_top_layers 1 -end_step 0
  grep "bapd: warning:" "$log" | grep -F "$warning" | grep -qF -- "-load_top_layers 4 (ceil(horizon / dx))" ||
    fail "shallow: no warning naming -load_top_layers 4"
  ! grep "bapd: warning:" "$log" | grep -q "load set 'bottom' grips" || fail "shallow: a warning for the bottom grip (2 horizons deep)"
  echo "ok   shallow: $(grep -F "$warning" "$log" | cut -c1-160)"
  finished inside "$TINY" -load_grip_placement inside -end_step 0
  [ "$(grep -c "bapd: warning:.*less than the horizon" "$log")" = 2 ] || fail "inside: want a warning for each one-row grip"
  finished deep "$TINY" -load_top_layers 4 -load_bottom_layers 4 -end_step 0
  ! grep -q "less than the horizon" "$log" || fail "deep: a warning for grips a horizon deep"
  echo "ok   deep and default grips: no warning"
  ;;
*)
  echo "unknown case $what"
  exit 1
  ;;
esac
echo "every case of $what ended as documented on $ranks rank(s)"
