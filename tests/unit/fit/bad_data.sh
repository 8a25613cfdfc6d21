#!/usr/bin/env bash
# bapd-fit refuses bad data with one "bapd-fit: error:" line and a non-zero exit, and
# fits good data with exit 0, a machine export too, given its specimen, and gives the
# toughness from a notched pure-shear curve beside the pure-shear one (usage:
# bad_data.sh path/to/bapd-fit tests/data/fit).
set -uo pipefail
fit="$1"
exports="$2"
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
expect_error compression "stretches > 1 once loading starts" "$(csv b.csv '# mode: uniaxial' 'stretch,stress_Pa' 1.0,0 1.2,20 0.9,30)"
expect_error negative "negative nominal stress" "$(csv c.csv '# mode: equibiaxial' 'stretch,stress_Pa' 1.1,10 1.2,-20 1.8,30)"
expect_error too_few "3 data point(s) for 4 parameter(s)" -law ogden "$(csv d.csv '# mode: uniaxial' 'stretch,stress_Pa' 1.1,10 1.2,20 1.8,30)"
expect_error no_units "column 'stress' (stress) needs its unit" "$(csv e.csv '# mode: uniaxial' 'stretch,stress' 1.1,10 1.2,20)"
expect_error no_mode "which test is it" "$(csv f.csv 'stretch,stress_Pa' 1.1,10 1.2,20)"
expect_error unknown_law "not a law bapd-fit knows" -law fung "$good"
expect_error undetermined "not determined by these data" -law mooney_rivlin "$good"
expect_error unknown_option "not an option of bapd-fit" -lwa gent "$good"
expect_error no_data "no data" -law gent
# a law that cannot fit: the data soften (stress falls with stretch past 3), which
# Gent, whose stiffness only grows, cannot follow with positive parameters
expect_error cannot_fit "did not converge\|cannot fit" -law gent "$(csv g.csv '# mode: uniaxial' 'stretch,stress_Pa' 1.5,1000 2,1500 3,1600 4,400 5,100)"

# a machine export: the specimen options before the file, in SI
export_csv="$exports/uniaxial_comma_units.csv"
expect_error no_gauge "column 'Extension (mm)' is the extension.*-fit_gauge_length" -fit_cross_section 1e-5 "uniaxial:$export_csv"
expect_error no_section "column 'Load (N)' is the force.*-fit_cross_section" -fit_gauge_length 0.02 "uniaxial:$export_csv"
expect_error width_alone "-fit_width needs -fit_thickness" -fit_gauge_length 0.02 -fit_width 0.005 "uniaxial:$export_csv"
expect_error after_the_file "-fit_cross_section comes after the last file" -fit_gauge_length 0.02 "uniaxial:$export_csv" -fit_cross_section 1e-5
expect_error bad_length "-fit_gauge_length 20mm: give the length in m" -fit_gauge_length 20mm "uniaxial:$export_csv"
expect_error export_no_mode "which test is it" -fit_gauge_length 0.02 -fit_cross_section 1e-5 "$export_csv"

# a notched pure-shear curve (the toughness): its peak at stretch 3, then the crack's drop
notched="$dir/notched.csv"
{ echo "stretch,nominal_stress_kPa"; for l in 1.5 2 2.5 2.9 3; do
    /usr/bin/python3 -c "l=$l; mu=4.55; Jm=162.6; print(f'{l},{0.73*mu*Jm*(l-l**-3)/(Jm-l*l-l**-2+2):.6f}')"
  done; echo "3.1,3.0"; echo "3.2,0"; } > "$notched"
rising="$(csv rising.csv stretch,nominal_stress_kPa 1.5,2 2,4 3,6)"
expect_error notched_alone "give that sheet's curve too" -fit_gauge_length 0.01 "notched_pure_shear:$notched"
expect_error notched_no_height "needs the sheet's height H0.*-fit_gauge_length" "$good" "notched_pure_shear:$notched"
expect_error notched_other_height "differs from the un-notched pure-shear curve's" -fit_gauge_length 0.01 "$good" \
  -fit_gauge_length 0.012 "notched_pure_shear:$notched"
expect_error notched_no_peak "is not in the data.*-fit_onset_stretch" -fit_gauge_length 0.01 "$good" "notched_pure_shear:$rising"
expect_error two_notched "a second notched curve" -fit_gauge_length 0.01 "$good" "notched_pure_shear:$notched" "notched_pure_shear:$notched"
expect_error onset_alone "-fit_onset_stretch is for the crack onset of a notched pure-shear test" -fit_onset_stretch 3 "$good"
expect_error onset_below_one "-fit_onset_stretch 0.9: give the crack onset's stretch, a number > 1" -fit_onset_stretch 0.9 "$good"
# Gent locks before stretch 20 (Jm 162.6): no Gamma there, its material still written
expect_error onset_past_the_lock "-law gent: the law is not defined at lambda_c = 20" -output_dir "$dir/lock" -law gent -fit_onset_stretch 20 \
  -fit_gauge_length 0.01 "$good" "notched_pure_shear:$notched"
[ -f "$dir/lock/material_gent.yaml" ] && ! grep -q "^failure:" "$dir/lock/material_gent.yaml" && echo "ok   its material is written without failure:" ||
  { echo "FAIL onset_past_the_lock: material_gent.yaml missing or with a failure section"; failures=$((failures + 1)); }
# the pair gives Gamma = W(3) H0 (165.4 J/m^2 for the paper's gel, H0 = 10 mm), printed and
# written as the failure section
if "$fit" -no_plot -output_dir "$dir/tough" -law gent -fit_gauge_length 0.01 "$good" "notched_pure_shear:$notched" > "$dir/log" 2>&1 &&
   grep -q "^  gent: Gamma = 165" "$dir/log" && grep -q "^  fracture_energy: 165" "$dir/tough/material_gent.yaml"; then
  echo "ok   the notched curve gives the toughness"
else echo "FAIL toughness: $(cat "$dir/log")"; failures=$((failures + 1)); fi

# the good file fits, exit 0, and writes the scene's material section
if "$fit" -no_plot -output_dir "$dir/out" -law gent "$good" > "$dir/log" 2>&1 && grep -q "^  model: gent" "$dir/out/material_gent.yaml"; then
  echo "ok   good data fits"
else echo "FAIL good data: $(cat "$dir/log")"; failures=$((failures + 1)); fi
# the export fits (a neo-Hookean law: its four points are no Gent curve), with the rest
# rows dropped and the conversion noted, and so does one with the section as width x thickness
if "$fit" -no_plot -output_dir "$dir/export" -law neo_hookean -fit_gauge_length 0.02 -fit_cross_section 1e-5 "uniaxial:$export_csv" \
     > "$dir/log" 2>&1 && grep -q "note: dropped 2 row(s) before loading starts" "$dir/log" &&
   grep -q "uniaxial_comma_units.csv,uniaxial,3,40000$" "$dir/export/data.csv" &&
   "$fit" -no_plot -output_dir "$dir/export2" -law neo_hookean -fit_gauge_length 0.01 -fit_width 0.05 -fit_thickness 0.002 \
     "pure_shear:$exports/pure_shear_semicolon_decimal_comma.csv" > "$dir/log2" 2>&1 &&
   grep -q "pure_shear,2,20000$" "$dir/export2/data.csv"; then
  echo "ok   machine exports fit"
else echo "FAIL machine export: $(cat "$dir/log" "$dir/log2" 2>/dev/null)"; failures=$((failures + 1)); fi
exit $((failures > 0))
