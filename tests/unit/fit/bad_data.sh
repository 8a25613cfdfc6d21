#!/usr/bin/env bash
# bapd-fit refuses bad data with one "bapd-fit: error:" line and a non-zero exit, and
# fits good data with exit 0 (usage: bad_data.sh path/to/bapd-fit).
set -uo pipefail
fit="$1"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
failures=0
good="$dir/good.csv"
{ echo "# mode: pure_shear"; echo "stretch,nominal_stress_kPa"
  for l in 1.2 1.5 2 2.5 3 3.5 4 4.5 5; do
    /usr/bin/python3 -c "l=$l; mu=4.55; Jm=162.6; print(f'{l},{mu*Jm*(l-l**-3)/(Jm-l*l-l**-2+2):.6f}')"
  done; } > "$good"

# expect_error NAME PATTERN ARGS...: exit status 1 and exactly one error line matching PATTERN
expect_error() {
  local name="$1" pattern="$2"; shift 2
  local err; err="$("$fit" -no_plot -output_dir "$dir/out" "$@" 2>&1 >/dev/null)"; local rc=$?
  local lines; lines="$(printf '%s\n' "$err" | grep -c '^bapd-fit: error: ')"
  if [ "$rc" -ne 1 ] || [ "$lines" -ne 1 ] || ! printf '%s' "$err" | grep -q -- "$pattern"; then
    echo "FAIL $name: rc=$rc, $lines error line(s), want /$pattern/: $err"; failures=$((failures + 1))
  else echo "ok   $name: $err"; fi
}
csv() { local f="$dir/$1"; shift; printf '%s\n' "$@" > "$f"; echo "$f"; }

expect_error non_monotone "must increase strictly" "$(csv a.csv '# mode: uniaxial' 'stretch,stress_Pa' 1.5,10 1.2,20 1.8,30)"
expect_error at_rest "stretches > 1" "$(csv b.csv '# mode: uniaxial' 'stretch,stress_Pa' 1.0,0 1.2,20 1.8,30)"
expect_error negative "negative nominal stress" "$(csv c.csv '# mode: equibiaxial' 'stretch,stress_Pa' 1.1,10 1.2,-20 1.8,30)"
expect_error too_few "3 data point(s) for 4 parameter(s)" -law ogden "$(csv d.csv '# mode: uniaxial' 'stretch,stress_Pa' 1.1,10 1.2,20 1.8,30)"
expect_error no_units "named with its unit" "$(csv e.csv '# mode: uniaxial' 'stretch,stress' 1.1,10 1.2,20)"
expect_error no_mode "which test is it" "$(csv f.csv 'stretch,stress_Pa' 1.1,10 1.2,20)"
expect_error unknown_law "not a law bapd-fit knows" -law fung "$good"
expect_error undetermined "not determined by these data" -law mooney_rivlin "$good"
expect_error unknown_option "not an option of bapd-fit" -lwa gent "$good"
expect_error no_data "no data" -law gent
# a law that cannot fit: the data soften (stress falls with stretch past 3), which
# Gent, whose stiffness only grows, cannot follow with positive parameters
expect_error cannot_fit "did not converge\|cannot fit" -law gent "$(csv g.csv '# mode: uniaxial' 'stretch,stress_Pa' 1.5,1000 2,1500 3,1600 4,400 5,100)"

# the good file fits, exit 0, and writes the scene's material section
if "$fit" -no_plot -output_dir "$dir/out" -law gent "$good" > "$dir/log" 2>&1 && grep -q "^  model: gent" "$dir/out/material_gent.yaml"; then
  echo "ok   good data fits"
else echo "FAIL good data: $(cat "$dir/log")"; failures=$((failures + 1)); fi
exit $((failures > 0))
