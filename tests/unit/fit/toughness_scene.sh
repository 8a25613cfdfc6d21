#!/usr/bin/env bash
# The toughness bapd-fit writes is a scene fragment bapd runs, and the example's is the
# one the paper's Gamma-driven scene uses (usage: toughness_scene.sh path/to/bapd-fit
# path/to/bapd SOURCE_DIR):
# 1. bapd-fit on examples/calibration's pure-shear and notched data writes what is
#    committed in examples/calibration/toughness (the YAML values and toughness.csv);
# 2. bapd, given examples/notched_pure_shear_gamma.yaml and then material_gent.yaml,
#    runs with the fitted law and the fracture energy the file gives (a step on a coarse grid);
# 3. that scene's own fracture_energy lies within the fitted Gamma's uncertainty.
set -uo pipefail
fit="$1"
bapd="$2"
src="$3"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }
example="$src/examples/calibration"

"$fit" -no_plot -law gent,arruda_boyce,yeoh,ogden,neo_hookean -output_dir "$dir/fit" -fit_gauge_length 0.01 \
  "$example/pure_shear_data.csv" -fit_width 0.07 -fit_thickness 0.003 "$example/notched_pure_shear_data.csv" > "$dir/fit.log" 2>&1 ||
  fail "bapd-fit on the example: $(cat "$dir/fit.log")"
for f in toughness.csv material_gent.yaml material_ogden.yaml material_arruda_boyce.yaml material_yeoh.yaml material_neo_hookean.yaml; do
  if diff <(grep -v '^#' "$example/toughness/$f") <(grep -v '^#' "$dir/fit/$f") > "$dir/diff" 2>&1; then echo "ok   $f is what bapd-fit writes"
  else fail "examples/calibration/toughness/$f differs from bapd-fit's: $(cat "$dir/diff")"; fi
done

yaml="$dir/fit/material_gent.yaml"
gamma="$(sed -n 's/^  fracture_energy: //p' "$yaml")"
[ -n "$gamma" ] || fail "no fracture_energy in material_gent.yaml: $(cat "$yaml")"
OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout 120 "$bapd" -options_file_yaml "$src/examples/notched_pure_shear_gamma.yaml" \
  -options_file_yaml "$yaml" -body_dx 1e-3 -end_step 1 -output_dir "$dir/run" > "$dir/run.log" 2>&1 || fail "bapd with the fitted YAML: $(cat "$dir/run.log")"
mu="$(sed -n 's/^  mu: //p' "$yaml")"
if grep -qF "Gamma = $gamma J/m^2" "$dir/run.log" && grep -q "material  gent, plane_stress: mu $(printf '%.6g' "$mu") Pa" "$dir/run.log"; then
  echo "ok   bapd runs the fitted law with Gamma = $gamma J/m^2"
else fail "bapd did not take the fitted material and Gamma = $gamma J/m^2: $(sed -n '1,12p' "$dir/run.log")"; fi

scene_gamma="$(sed -n 's/^  fracture_energy: *\([0-9.]*\).*/\1/p' "$src/examples/notched_pure_shear_gamma.yaml")"
read -r fitted sigma <<< "$(awk -F, '$1 == "gent" { print $6, $7 }' "$example/toughness/toughness.csv")"
if awk -v s="$scene_gamma" -v g="$fitted" -v u="$sigma" 'BEGIN { d = s - g; exit !(s != "" && (d < 0 ? -d : d) <= u) }'; then
  echo "ok   examples/notched_pure_shear_gamma.yaml's Gamma $scene_gamma J/m^2 is the example's $fitted +- $sigma"
else fail "examples/notched_pure_shear_gamma.yaml's Gamma '$scene_gamma' is not the example's $fitted +- $sigma J/m^2"; fi
exit $((failures > 0))
