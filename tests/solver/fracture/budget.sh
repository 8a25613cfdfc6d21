#!/usr/bin/env bash
# A crack that the fracture energy drives through a notched pure-shear sheet (Gamma =
# 165 J/m^2, dx = 1 mm, 30 mm wide, 10 mm notch, pulled to stretch 3.3 in 0.25 s):
# the energy balance of history.csv (docs/method.md 5.3) must close to 1 % of the grips'
# work once the crack has crossed the sheet. With one breaking pass a step
# (-failure_passes 1) it is off by -26 %: the bonds that a pass loads past the
# criterion stay for a step near the Gent chain limit, where the tip is thousands of
# times as stiff as the body at rest, and points are thrown off with energy from
# nowhere (docs/method.md 5.2). Measured with the passes until none breaks: 0.02 %.
#   budget.sh   (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
set -uo pipefail
src="$BAPD_SOURCE_DIR"
work="fracture_budget"
rm -rf "$work" && mkdir -p "$work" || exit 1
source "$src/tests/solver/fracture/common.sh"
run_sheet "$work/run" -load_schedule 0,1,0.25,3.3 -end_time 0.25 -output_interval 50
read -r work_J residual_J crack_m < <(awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { w = $c["top_work_J"] + $c["bottom_work_J"]; r = $c["energy_balance_residual_J"]; l = $c["crack_length_m"] } END { print w, r, l }' "$work/run/history.csv")
echo "grips' work $work_J J, residual $residual_J J, crack length $crack_m m"
# The crack must cross the ligament (20 mm from the mouth, 10 mm of it new), or the case tests nothing.
awk -v l="$crack_m" 'BEGIN { exit !(l > 0.025) }' || fail "the crack ran only to $crack_m m from the mouth: the case tests nothing"
# 1 %: the budget's own target (docs/method.md 5.3, the run's warning); the integrator's
# O(dt^2) share is ~1e-6 of the work here (the residual before the onset).
awk -v w="$work_J" -v r="$residual_J" 'BEGIN { exit !(r < 0 ? -r < 1e-2 * w : r < 1e-2 * w) }' ||
  fail "the energy balance is off by $residual_J J of $work_J J (more than 1 %)"
echo "fracture budget: ok"
