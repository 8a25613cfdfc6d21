#!/usr/bin/env bash
# What a run tells its user: progress lines with dt and energies, about 20
# of them and about 20 field files by simulated time, and an end summary that names
# every file written with its size, and only those.
#   summary.sh RANKS        (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
set -uo pipefail
ranks="$1"
src="$BAPD_SOURCE_DIR"
work="input_summary_np$ranks"
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }

# The tiny sheet with a step 10x shorter than its stable one after the first half
# (restart with -time_step_safety): counts by steps sized at the start would double.
# Progress lines by simulated time only (-progress_wall_interval 0: none by wall time
# on a slow machine).
scene="$src/tests/data/scenes/tiny.yaml"
common=(-progress_interval 0 -progress_wall_interval 0 -output_fields -output_final_state -checkpoint_interval 40 -output_dir out)
timeout 120 "$src/run_mpi.sh" -n "$ranks" "$scene" "${common[@]}" -end_step 25 > first.log 2>&1 || fail "first half: exit $?"
timeout 120 "$src/run_mpi.sh" -n "$ranks" "$scene" "${common[@]}" -restart out/checkpoint.h5 -end_step 100000 \
  -time_step_safety 0.08 > run.log 2>&1 || fail "second half: exit $?"

# Progress lines: dt, kinetic and internal energy; one per 1/20 of the (second) run's
# end time from the restart on, whatever the step.
progress=$(grep -c "^step .* dt .* s .*KE .* J  IE .* J" run.log)
((progress >= 10 && progress <= 11)) || fail "$progress progress lines with dt, KE and IE for the second half (10 or 11 expected)"

# Field files: those on disk, those fields.xdmf lists and the summary's count agree.
on_disk=$(ls out/fields/*.h5 2>/dev/null | wc -l)
listed=$(grep -c "<Grid Name=\"step" out/fields.xdmf)
summary=$(grep -oE "[0-9]+ field file\(s\)" run.log | grep -oE "^[0-9]+")
[ "$on_disk" = "$listed" ] || fail "$on_disk field files on disk, $listed in fields.xdmf"
[ "$on_disk" = "$summary" ] || fail "$on_disk field files on disk, the summary says ${summary:-none}"
((on_disk >= 21 && on_disk <= 22)) || fail "$on_disk field files (t = 0 and one per 1/20 of the end time expected)"

# The summary names every file written, with a size, and the sizes are the files'.
for f in history.csv fields.xdmf checkpoint.h5 final_state.csv broken_bonds.csv; do
  grep -qE "^  $f +[0-9.]+ (B|kB|MB)" run.log || fail "the summary does not list $f with its size"
  [ -s "out/$f" ] || fail "out/$f missing or empty"
done
grep -q "static_states.csv" run.log && fail "the summary names static_states.csv, which this run did not write"
bytes=$(stat -c %s out/history.csv)
shown=$(grep -E "^  history.csv " run.log | awk '{print $2, $3}')
expected=$(/usr/bin/python3 -c "b=$bytes; print(f'{b} B' if b<1000 else f'{b/1e3:.1f} kB' if b<1e6 else f'{b/1e6:.1f} MB')")
[ "$shown" = "$expected" ] || fail "history.csv is $bytes bytes; the summary says '$shown'"

if ((failures)); then
  echo "$failures check(s) failed; the run printed:"
  sed 's/^/    | /' run.log
  exit 1
fi
echo "summary: $progress progress lines, $on_disk field files, every file listed ($ranks rank(s))"
