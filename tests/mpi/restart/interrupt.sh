#!/usr/bin/env bash
# kill -USR1 in the middle of a run writes a checkpoint and the run goes on; kill
# -TERM then makes every rank stop at the same step, write a checkpoint and exit
# non-zero with one message; `bapd -restart FILE` alone (the
# scene, the output directory and the run length come from the checkpoint) then
# finishes the run, on another number of ranks, with the same results as a run that
# was never interrupted.
set -euo pipefail
source "$BAPD_SOURCE_DIR/tests/mpi/restart/common.sh"
work="restart_interrupt"
rm -rf "$work"; mkdir -p "$work"
# 600 steps, long enough to be interrupted after step 100, before the crack starts
# (its first bonds break near step 430, 13 by step 590): the restarted run breaks the
# bonds. (Beyond, the crack runs and each step costs the crack-tip search's force
# evaluations: 900 steps cost twice the CPU and prove nothing more here.)
# On a grid twice as fine as the other restart tests: the signals must arrive while it
# runs, and at dx = 0.5 mm 900 steps take barely a second.
end=600
scene=("${NOTCHED[@]}" "${FRACTURE[@]}" -body_dx 0.00025 -end_step $end -progress_interval 10)
run 2 "$work/whole" "${scene[@]}"

# Open MPI's mpiexec passes SIGUSR1 on to the ranks (checkpoint, go on) and SIGTERM
# too (checkpoint, stop), killing them 1 s after a SIGTERM: time enough here.
mpiexec -n 2 --oversubscribe --bind-to none "$BAPD_EXE" "${scene[@]}" -output_dir "$work/cut" > "$work/cut.log" 2>&1 &
pid=$!
# wait_for PATTERN: until a line of cut.log matches (the run still going).
wait_for() {
  for _ in $(seq 1200); do
    grep -q -E "$1" "$work/cut.log" 2> /dev/null && return 0
    kill -0 $pid 2> /dev/null || { cat "$work/cut.log"; fail "the run ended before it could be interrupted"; }
    sleep 0.1
  done
  fail "timed out waiting for '$1'"
}
wait_for '^step +[1-9][0-9]{2} '
kill -USR1 $pid
wait_for '^Checkpoint \(SIGUSR1\)'
usr1_step=$(sed -n 's/^Checkpoint (SIGUSR1): step \([0-9]*\),.*/\1/p' "$work/cut.log")
kill -TERM $pid
set +e
wait $pid
status=$?
set -e
cat "$work/cut.log"
[ "$status" -ne 0 ] || fail "an interrupted run must exit non-zero"
[ "$status" -lt 128 ] || fail "bapd died on a signal (exit status $status) instead of stopping cleanly"
[ -f "$work/cut/checkpoint.h5" ] || fail "no checkpoint after SIGTERM"
[ ! -e "$work/cut/checkpoint.h5.tmp" ] || fail "a temporary checkpoint was left behind"
[ "$(grep -c 'bapd: error:' "$work/cut.log")" = 1 ] || fail "expected exactly one error line"
# mpiexec passes the one SIGUSR1 to both ranks, which may see it a step apart: still one checkpoint.
[ "$(grep -c '^Checkpoint (SIGUSR1)' "$work/cut.log")" = 1 ] || fail "one SIGUSR1 must write one checkpoint"
grep -q "bapd: error: interrupted by SIGTERM at step" "$work/cut.log" || fail "no interruption message"
step=$(sed -n 's/^Checkpoint (interrupted): step \([0-9]*\),.*/\1/p' "$work/cut.log")
echo "checkpoint on SIGUSR1 at step $usr1_step, interrupted by SIGTERM at step $step"
[ -n "$step" ] && [ "$step" -gt "$usr1_step" ] && [ "$step" -lt $end ] || fail "SIGUSR1 must not stop the run, SIGTERM must stop it before its end"

mpiexec -n 3 --oversubscribe --bind-to none "$BAPD_EXE" -restart "$work/cut/checkpoint.h5" > "$work/restart.log" 2>&1 ||
  { cat "$work/restart.log"; fail "the restart failed"; }
grep -q "^Finished: $end steps" "$work/restart.log" || { cat "$work/restart.log"; fail "the restart did not run to the end"; }
python3 "$BAPD_SOURCE_DIR/tests/mpi/compare_runs.py" --tolerance 0 --expect-broken "$work/whole" "$work/cut"
echo "interrupt and restart: same results as the uninterrupted run"
