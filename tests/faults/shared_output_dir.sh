#!/usr/bin/env bash
# Two runs into one output directory: the second, started while the first runs, stops
# at once with one `bapd: error:` line naming the directory, the other run and the fix,
# exits non-zero and writes nothing there; the first goes on undisturbed (rank 0 holds
# a lock on <dir>/.bapd.lock for the run's life). The lock dies with its run: after
# the first run's lock holder is killed (SIGKILL), the next run into the directory starts.
#   shared_output_dir.sh RANKS
source "$BAPD_SOURCE_DIR/tests/faults/common.sh"
source "$BAPD_SOURCE_DIR/tests/faults/long_scene.sh"
ranks="$1"
work="faults_shared_output_dir_np$ranks"
rm -rf "$work" && mkdir -p "$work" || exit 1
out="$work/out"

start_long "$work/first.log" "$ranks" -output_dir "$out"
first=$PID
bounded "$work/second.log" "$ranks" "$TINY" -output_dir "$out" -output_final_state
stopped_cleanly "$out" "in use by another run" "-output_dir $out" "wait until that run ends"
stopped_saying "process [0-9]+ on host"
grep -q "^step " "$log" && fail "the second run took steps"
[ ! -e "$out/final_state.csv" ] || fail "the second run wrote final_state.csv into the first run's directory"
kill -0 "$first" 2> /dev/null || fail "the first run stopped when the second was refused"
ok "a second run into a directory in use on $ranks rank(s)"

# The first run's lock holder killed: the kernel drops its lock; the first run's
# history stays whole, one header and increasing steps (a second writer would have cut it).
holder=$(grep 'bapd: error:' "$log" | sed -n 's/.*process \([0-9]*\) on host.*/\1/p')
[ -n "$holder" ] && [ "$(cat "/proc/$holder/comm" 2> /dev/null)" = bapd ] || fail "the error line does not name the first run's bapd process"
kill -KILL "$holder"
finish_long
((STATUS != 0 && STATUS != 124)) || fail "the first run exited with $STATUS after its rank 0 was killed"
[ "$(grep -c '^step,' "$out/history.csv")" = 1 ] || fail "history.csv has more than one header"
whole_rows "$out/history.csv"
log="$work/first.log" # (for fail's listing)
grep -q "mouth_ux_m" "$out/history.csv" || fail "history.csv is not the first run's"
bounded "$work/third.log" "$ranks" "$TINY" -output_dir "$out"
((STATUS == 0)) || fail "a run into the directory of a killed run is refused (a stale lock?)"
echo "ok   the lock died with the killed run: the next run into $out starts"
