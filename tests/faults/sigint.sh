#!/usr/bin/env bash
# SIGINT (Ctrl-C) to run_mpi.sh: Open MPI's mpiexec would pass it on as
# SIGTERM and kill the ranks 1 s later; run_mpi.sh passes it on as SIGUSR2 (at once)
# and names it. The run writes a checkpoint, says "interrupted by SIGINT" in one line,
# exits non-zero (not by a signal), and the checkpoint continues the run.
# Output into a pipe whose reader ends (| head): mpiexec would abort the ranks with
# SIGTERM; run_mpi.sh stops the run as for SIGTERM and names SIGPIPE. SIGHUP, and a
# SIGINT before the ranks can hear it, are named too.
#   sigint.sh RANKS
source "$BAPD_SOURCE_DIR/tests/faults/common.sh"
source "$BAPD_SOURCE_DIR/tests/faults/long_scene.sh"
ranks="$1"
work="faults_sigint_np$ranks"
rm -rf "$work" && mkdir -p "$work" || exit 1

# (SIGHUP: mpiexec passed it on as SIGTERM, and named it so)
for sig in INT TERM HUP; do
  start_long "$work/$sig.log" "$ranks" -output_dir "$work/$sig"
  # Twice, 0.3 s apart: one request can arrive twice (`timeout` passes a signal to
  # run_mpi.sh and to its process group), and must still stop cleanly, not kill.
  kill -$sig $PID
  sleep 0.3
  kill -$sig $PID 2> /dev/null
  finish_long
  stopped_cleanly "interrupted by SIG$sig at step" "-restart $work/$sig/checkpoint.h5"
  [ -f "$work/$sig/checkpoint.h5" ] || fail "no checkpoint after SIG$sig"
  [ ! -e "$work/$sig/checkpoint.h5.tmp" ] || fail "a temporary checkpoint was left behind"
  whole_rows "$work/$sig/history.csv"
  ok "SIG$sig on $ranks rank(s), stopped ${SECONDS_LEFT} s later"
done
# (the first lines to head, stderr to the log: as a user would run it)
timeout 60 "$BAPD_SOURCE_DIR/run_mpi.sh" -n "$ranks" "${LONG[@]}" -output_dir "$work/PIPE" 2> "$work/PIPE.log" | head -n 3 > /dev/null
STATUS=${PIPESTATUS[0]}
log="$work/PIPE.log"
stopped_cleanly "interrupted by SIGPIPE at step" "-restart $work/PIPE/checkpoint.h5"
whole_rows "$work/PIPE/history.csv"
ok "the reader of the output (head) ended on $ranks rank(s)"
# A Ctrl-C in the first second, before the ranks have set their handlers (or before
# mpiexec has started them): one line naming SIGINT, exit 1, not a death by SIGUSR2.
timeout 60 "$BAPD_SOURCE_DIR/run_mpi.sh" -n "$ranks" "${LONG[@]}" -output_dir "$work/EARLY" > "$work/EARLY.log" 2>&1 &
PID=$!
sleep 0.3
kill -INT $PID
finish_long
log="$work/EARLY.log"
stopped_cleanly "interrupted by SIGINT"
ok "SIGINT 0.3 s after the start on $ranks rank(s), stopped ${SECONDS_LEFT} s later"
step=$(sed -n 's/^Checkpoint (interrupted): step \([0-9]*\),.*/\1/p' "$work/INT.log")
bounded "$work/continued.log" "$ranks" -restart "$work/INT/checkpoint.h5" -end_step $((step + 20)) -output_dir "$work/continued"
((STATUS == 0)) || fail "the checkpoint written on SIGINT does not continue"
grep -q "^Restart from .*step $step," "$work/continued.log" || fail "the continuation did not start at step $step"
echo "ok   the SIGINT checkpoint (step $step) continues"
