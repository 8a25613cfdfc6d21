#!/usr/bin/env bash
# run_mpi.sh killed by SIGKILL (a batch system's hard kill of the job script, kill -9):
# it can pass nothing on, and mpiexec runs in a session of its own; without more it
# would run on, with the ranks, for ever. mpiexec gets SIGTERM when run_mpi.sh dies
# (setpriv --pdeathsig): within seconds no mpiexec or bapd process of the run is left,
# and the output directory keeps what was written; its signal file
# ($TMPDIR/bapd_signal.*, which its exit trap would have removed) is removed too.
#   killed_launcher.sh RANKS
source "$BAPD_SOURCE_DIR/tests/faults/common.sh"
source "$BAPD_SOURCE_DIR/tests/faults/long_scene.sh"
ranks="$1"
work="faults_killed_launcher_np$ranks"
rm -rf "$work" && mkdir -p "$work" || exit 1
command -v setpriv > /dev/null || { echo "SKIP: no setpriv (util-linux) here"; exit 77; }
log="$work/run.log"
# run_mpi.sh's own files apart from other tests' (short: Open MPI's sockets live there)
TMPDIR="$(mktemp -d /tmp/bapd_killed_launcher.XXXXXX)" || exit 1
export TMPDIR
trap 'rm -rf "$TMPDIR"' EXIT
# Not through `timeout` (start_long): SIGKILL goes to run_mpi.sh itself.
"$BAPD_SOURCE_DIR/run_mpi.sh" -n "$ranks" "${LONG[@]}" -output_dir "$work/out" > "$log" 2>&1 &
launcher=$!
for _ in $(seq 600); do grep -q '^step ' "$log" 2> /dev/null && break; sleep 0.1; done
grep -q '^step ' "$log" || { kill -TERM $launcher; fail "the run did not start stepping"; }
# The run's processes: every one whose command line holds this output directory.
left() { pgrep -f -- "-output_dir $work/out" | while read -r p; do case "$(cat /proc/$p/comm 2> /dev/null)" in bapd | mpiexec | orterun | prterun) echo "$p" ;; esac; done; }
[ -n "$(left)" ] || fail "no mpiexec or bapd process of the run found"
kill -KILL $launcher
wait $launcher 2> /dev/null
for _ in $(seq 100); do [ -z "$(left)" ] && break; sleep 0.1; done
orphans="$(left)"
if [ -n "$orphans" ]; then
  # (the test's own clean-up: these are the processes it started)
  kill -KILL $orphans 2> /dev/null
  fail "processes of the run were left running after run_mpi.sh was killed: $(echo $orphans)"
fi
whole_rows "$work/out/history.csv"
for _ in $(seq 50); do [ -z "$(ls "$TMPDIR" | grep bapd_signal)" ] && break; sleep 0.1; done
[ -z "$(ls "$TMPDIR" | grep bapd_signal)" ] || fail "run_mpi.sh's signal file was left in TMPDIR: $(ls "$TMPDIR")"
echo "ok   run_mpi.sh killed by SIGKILL on $ranks rank(s): no mpiexec or bapd process left within 10 s, no signal file; history.csv whole"
