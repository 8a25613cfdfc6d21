#!/usr/bin/env bash
# What a researcher reads off a coarse run: history.csv has at least
# -output_history_rows rows over the end time whatever the step (pure shear at
# dx = 1 mm), the grips' displacement columns equal the displacement the rigid grips
# impose, the rows by load change no result (the same final state, bonds and rows on
# the -output_interval grid with the rows off), progress lines come by wall time with
# -progress_wall_interval, and bad values of both options are refused.
#   history_rows.sh RANKS   (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
set -uo pipefail
ranks="$1"
src="$BAPD_SOURCE_DIR"
work="input_history_rows_np$ranks"
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }

# Pure shear (examples/pure_shear.yaml) at dx = 1 mm: its -output_interval 500 gave 6
# rows over the schedule. Rigid grips, so that a grip's points all move by the imposed
# u = (lambda - 1) L (L = the body's height, 10 mm); the first quarter of the schedule
# (~560 steps, ~1 row every 500 without the rows by load).
scene=(-options_file_yaml "$src/examples/pure_shear.yaml" -body_dx 0.001 -load_grip_field rigid -end_time 0.25
       -output_final_state -progress_interval 1000000)
run() {
  local name="$1"
  shift
  timeout 300 "$src/run_mpi.sh" -n "$ranks" "${scene[@]}" -output_dir "$name" "$@" > "$name.log" 2>&1 || fail "$name: exit $?"
}
run rows -progress_wall_interval 0
run off -output_history_rows 0 -progress_wall_interval 1e-9

/usr/bin/python3 - rows/history.csv off/history.csv << 'EOF' || failures=$((failures + 1))
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
off = list(csv.DictReader(open(sys.argv[2])))
bad = []
# At least 100 rows after step 0 (the default -output_history_rows), each step once.
if len(rows) < 101:
    bad.append(f"{len(rows)} rows, want >= 101 (step 0 and one per 1/100 of the end time)")
steps = [int(r["step"]) for r in rows]
if steps != sorted(set(steps)):
    bad.append("the rows' steps are not increasing (a step written twice?)")
# A row at the first step at or past each 1/100 of the end time: no gap over 1/100.
times = [float(r["time_s"]) for r in rows]
gap = max(b - a for a, b in zip(times, times[1:]))
if gap > 0.25 / 100 + 1e-3:  # (the step is 4.4e-4 s)
    bad.append(f"a gap of {gap:.3g} s between rows, more than 1/100 of the end time and a step")
# The grips' columns: top y = (lambda - 1) L, L = 0.010 m; x fixed: 0; the bottom held: 0.
# Relative round-off of the mean of equal values (a reproducible sum): ~1e-15.
for r in rows:
    want = (float(r["stretch"]) - 1.0) * 0.010
    got = float(r["top_displacement_y_m"])
    if abs(got - want) > 1e-12 * max(abs(want), 1e-3):
        bad.append(f"step {r['step']}: top_displacement_y_m {got!r}, the grip imposes {want!r}")
        break
    for c in ("top_displacement_x_m", "bottom_displacement_x_m", "bottom_displacement_y_m"):
        if float(r[c]) != 0.0:
            bad.append(f"step {r['step']}: {c} = {r[c]}, the grip holds it at 0")
            break
if float(rows[-1]["top_displacement_y_m"]) <= 0:
    bad.append("the top grip never moved")
# The rows by load read the state only: the run without them has a subset of the rows,
# the same bits, and no other row.
by_step = {r["step"]: r for r in rows}
for r in off:
    if by_step.get(r["step"]) != r:
        bad.append(f"step {r['step']}: the row of the run without rows by load differs or is missing")
        break
if len(off) >= len(rows) / 10:
    bad.append(f"{len(off)} rows without the rows by load: the comparison proves nothing")
for b in bad:
    print("FAIL", b)
print(f"{len(rows)} rows by load, {len(off)} without; the grips' columns are the imposed displacement")
sys.exit(1 if bad else 0)
EOF
for f in final_state.csv broken_bonds.csv; do
  cmp -s rows/$f off/$f || fail "$f differs with and without the rows by load"
done

# Progress lines: with -progress_wall_interval 1e-9 one a step; with 0 (and
# -progress_interval 1000000) none.
steps=$(grep -oE "^Finished: [0-9]+ steps" off.log | grep -oE "[0-9]+")
lines=$(grep -c "^step .* wall .* left" off.log)
[ -n "$steps" ] && [ "$lines" = "$steps" ] || fail "$lines progress lines with -progress_wall_interval 1e-9, want one a step (${steps:-?})"
lines=$(grep -c "^step .* wall .* left" rows.log)
[ "$lines" = 0 ] || fail "$lines progress lines with -progress_wall_interval 0 and -progress_interval 1000000, want none"

# Bad values: one bapd: error line naming the option, non-zero exit, no step.
for bad in "-output_history_rows -1" "-progress_wall_interval -5"; do
  name="${bad%% *}"
  # shellcheck disable=SC2086
  timeout 60 "$src/run_mpi.sh" -n "$ranks" "${scene[@]}" -output_dir refused $bad > refused.log 2>&1 && fail "$bad: exit 0"
  grep -q "^bapd: error: $name" refused.log || { cat refused.log; fail "$bad: no 'bapd: error: $name' line"; }
  grep -q "^step " refused.log && fail "$bad: steps were taken"
done

((failures == 0)) && echo "history rows, grip columns and progress by wall time: ok"
exit $((failures > 0))
