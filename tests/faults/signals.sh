#!/usr/bin/env bash
# Signals sent to one rank, and a stop asked for during a long set-up. Each run stops
# within seconds with one `bapd: error:` line, a non-zero exit, no PETSc stack, no
# process of the run left, and what was written whole:
#   SIGQUIT to one rank: as SIGTERM, a checkpoint and "interrupted by SIGQUIT at step N";
#   SIGSEGV, SIGBUS to one rank: "rank R stopped by SIGSEGV, sent by process P", every
#     rank stopped (no checkpoint: the process that got it may be damaged);
#   SIGTERM during the set-up of a large body (590 400 points: about a minute of set-up on
#     this sheet): the run ends 10 s later, not after the set-up, saying so.
#   signals.sh RANKS
source "$BAPD_SOURCE_DIR/tests/faults/common.sh"
source "$BAPD_SOURCE_DIR/tests/faults/long_scene.sh"
ranks="$1"
work="faults_signals_np$ranks"
rm -rf "$work" && mkdir -p "$work" || exit 1
victim_rank=$((ranks - 1))

# rank_pid OUT K: the process id of rank K of the run writing into OUT (the ranks are
# started in rank order by mpiexec; their PMIx rank is in the environment).
rank_pid() {
  local p
  for p in $(pgrep -f -- "-output_dir $1"); do
    [ "$(cat /proc/$p/comm 2> /dev/null)" = bapd ] || continue
    tr '\0' '\n' < /proc/$p/environ 2> /dev/null | grep -qx "OMPI_COMM_WORLD_RANK=$2" && echo "$p" && return
  done
}
# none_left OUT: no bapd or mpiexec process of the run writing into OUT.
none_left() {
  local p
  for p in $(pgrep -f -- "-output_dir $1"); do
    case "$(cat /proc/$p/comm 2> /dev/null)" in bapd | mpiexec) fail "process $p of the run is still there after it ended" ;; esac
  done
}

# The signal goes to the rank, which stops with a non-zero exit; on 1 rank mpiexec then
# waits 2.1 s for ranks that are not there (bad_input.sh explains). Not in the set-up
# case below, whose SIGTERM reaches mpiexec too.
((ranks == 1)) && export OMPI_MCA_odls_base_sigkill_timeout=0
for sig in QUIT SEGV BUS; do
  out="$work/$sig"
  start_long "$work/$sig.log" "$ranks" -output_dir "$out"
  # The lookup is retried for up to 5 s: under load a rank's /proc entries were missed
  # once in a few runs; a miss that lasts names what was seen.
  pid=
  for _ in $(seq 50); do
    pid=$(rank_pid "$out" $victim_rank)
    [ -n "$pid" ] && break
    sleep 0.1
  done
  [ -n "$pid" ] || fail "rank $victim_rank of the run not found; processes of the run: $(pgrep -a -f -- "-output_dir $out" | cut -c1-80 | tr '\n' ';')"
  kill -$sig "$pid"
  finish_long
  if [ $sig = QUIT ]; then
    stopped_cleanly "interrupted by SIGQUIT at step" "-restart $out/checkpoint.h5"
    [ -f "$out/checkpoint.h5" ] || fail "no checkpoint after SIGQUIT"
  else
    stopped_cleanly "rank $victim_rank stopped by SIG$sig" "sent by process"
  fi
  none_left "$out"
  whole_rows "$out/history.csv"
  ok "SIG$sig to rank $victim_rank of $ranks, stopped ${SECONDS_LEFT} s later"
done

# SIGTERM to run_mpi.sh 1 s into the set-up of a body of 590 400 points, whose set-up
# with the power iteration's 61 force evaluations for the stable step (about twice the
# 28 s and 615 MB of 304 235 points on one idle core; half the time on two) outlasts the
# signal's 1 s and the 10 s of grace. The handlers are in place before the scene is
# printed (errors.cpp): 1 s after the scene line the signal lands inside the set-up.
# The run ends 10 s after the signal whatever the body's size. (A body of 304 235 points
# with the Krylov search's 14 evaluations, or even with the 61, set up on two idle cores
# within 14 s.)
unset OMPI_MCA_odls_base_sigkill_timeout
out="$work/setup"
timeout 60 "$BAPD_SOURCE_DIR/run_mpi.sh" -n "$ranks" "${LONG[@]}" -body_dx 0.000025 -time_step_estimate power \
  -output_dir "$out" > "$work/setup.log" 2>&1 &
PID=$!
log="$work/setup.log"
for _ in $(seq 300); do grep -q '^Scene' "$log" 2> /dev/null && break; sleep 0.1; done
sleep 1
grep -q '^step ' "$log" && fail "the set-up ended before the signal: the case tests nothing"
kill -TERM $PID
finish_long
grep -q '^Time stepping:' "$log" && fail "the set-up ended within the signal's 1 s and the 10 s of grace: the case tests nothing (give it a larger body)"
stopped_cleanly "interrupted by SIGTERM" "during the set-up"
python3 -c "import sys; sys.exit(float(sys.argv[1]) > 25)" "$SECONDS_LEFT" || fail "the run took ${SECONDS_LEFT} s to stop after SIGTERM in the set-up"
none_left "$out"
ok "SIGTERM during the set-up on $ranks rank(s), stopped ${SECONDS_LEFT} s later"
