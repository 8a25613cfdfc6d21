#!/usr/bin/env bash
# A rank killed by SIGKILL (the out-of-memory killer, a batch time limit) cannot report
# anything itself, and mpiexec -q says nothing: run_mpi.sh must print one line naming
# the signal, exit with the rank's status, and leave what was written in place.
#   killed_rank.sh        (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
set -uo pipefail
work="faults_killed_rank"
rm -rf "$work" && mkdir -p "$work" || exit 1
fail() { echo "FAIL: $*"; sed 's/^/    | /' "$work/run.log"; exit 1; }
# The tiny sheet for much longer than it takes to kill it: ~10^5 steps.
timeout 100 "$BAPD_SOURCE_DIR/run_mpi.sh" -n 2 "$BAPD_SOURCE_DIR/tests/data/scenes/tiny.yaml" -load_schedule 0,1,100,1.05 \
  -output_dir "$work/out" -output_interval 10 -progress_interval 100 > "$work/run.log" 2>&1 &
pid=$!
for _ in $(seq 600); do grep -q '^step ' "$work/run.log" 2> /dev/null && break; sleep 0.1; done
grep -q '^step ' "$work/run.log" || fail "the run did not start stepping"
victim=$(pgrep -f -- "-output_dir $work/out" | while read -r p; do [ "$(cat /proc/$p/comm)" = bapd ] && echo "$p"; done | tail -1)
[ -n "$victim" ] || fail "no bapd process found"
kill -KILL "$victim"
wait $pid
status=$?
((status != 124)) || fail "the run hung after a rank was killed"
((status == 137)) || fail "exit status $status, expected 137 (128 + SIGKILL)"
[ "$(grep -c 'bapd: error:' "$work/run.log")" = 1 ] || fail "expected exactly one error line"
grep -q 'bapd: error: a bapd process was killed by SIGKILL' "$work/run.log" || fail "the error line does not name SIGKILL"
[ "$(wc -l < "$work/out/history.csv")" -ge 2 ] || fail "history.csv lost the rows written before the kill"
echo "ok   killed rank: exit $status, $(grep 'bapd: error:' "$work/run.log" | cut -c1-80)..."
