#!/usr/bin/env bash
# The short version of paper scene 3: examples/notched_pure_shear.yaml on a
# coarser grid (dx = 0.5 mm), half as wide (35 mm, 10 mm notch: in pure shear the
# crack's driving force does not depend on the width or the notch length once both
# are several heights), loaded 3 x faster to stretch 2.2, where nothing breaks yet,
# then 1.5 x faster and only to stretch 3.05 (the crack starts near 2.83, 0.1 s or 20
# damping times after the change of rate, and is through at 3.00; beyond, the halves
# only retract, 1 100 more steps at 3.4; with 1.5 x from the start the crack started at
# the same stretch and stress, 650 steps later). The crack must
# start, run straight along the notch line through the whole width, symmetric about
# it, and give the same answer bit for bit on 1 and 2 ranks; the step must have been
# shortened while it ran (-time_step_travel), without which this scene blows up as the
# crack starts (docs/stability.md, section 5). check_notched.py has the figures.
#   notched_short.sh        (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
set -uo pipefail
work="validation_notched_short"
rm -rf "$work" && mkdir -p "$work" || exit 1
scene=(-options_file_yaml "$BAPD_SOURCE_DIR/examples/notched_pure_shear.yaml"
       -body_dx 0.0005 -body_width 0.035 -body_notches 0.025,0.005,0.035,0.005
       -probe_notch_mouth_top_at 0.035,0.0052 -probe_notch_mouth_bottom_at 0.035,0.0048
       -load_schedule 0,1,0.1,2.2,0.2417,3.05 -output_interval 10 -progress_interval 1000000 -output_final_state)
status=0
# Both runs at once, so that the two cores the test holds (PROCESSORS 2) are busy for
# its whole length, not one of them idle while the 1-rank run goes alone.
pids=()
for n in 1 2; do
  timeout 600 mpiexec -n $n --oversubscribe --bind-to none "$BAPD_EXE" "${scene[@]}" -output_dir "$work/np$n" \
    > "$work/np$n.log" 2>&1 &
  pids+=($!)
done
for n in 1 2; do
  if ! wait "${pids[n - 1]}"; then
    tail -20 "$work/np$n.log"
    echo "FAIL: the short notched scene did not run to the end on $n rank(s)"
    status=1
  fi
done
((status == 0)) || exit 1
for f in history.csv final_state.csv broken_bonds.csv; do
  if cmp -s "$work/np1/$f" "$work/np2/$f"; then echo "ok   $f identical on 1 and 2 ranks"
  else echo "FAIL $f differs between 1 and 2 ranks"; status=1; fi
done
/usr/bin/python3 "$BAPD_SOURCE_DIR/tests/validation/check_notched.py" "$work/np1" "$work/np1.log" || status=1
exit $status
