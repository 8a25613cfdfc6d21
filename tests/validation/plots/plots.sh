#!/usr/bin/env bash
# The plotting scripts label what they draw and keep the grips apart:
# - plot_labels.py's examples (doctest): top_nominal_stress_Pa is "top nominal stress
#   (kPa)" for gel stresses, the stretch dimensionless, a displacement in mm;
# - plot_history.py names both axes with quantity and unit on a real history.csv, the
#   unit suiting the references drawn with it too;
# - plot_fields.py on the tiny sheet (20 x 20 points, grips outside at the top and the
#   bottom): the grip points it draws apart are exactly those whose reference position
#   is outside the 10 mm x 10 mm specimen (counted here from the file), its colour
#   scale is the specimen's range of sigma_yy alone, and the component is in the file
#   name; with grips of different depths (3 rows at the top, 6 at the bottom) the
#   files' load_set dataset still gives them exactly, and without it (an older bapd's
#   files) the mirrored guess is wrong and --specimen 0.01 0.01 puts it right;
# - plot_fit.py's legend gives each law's fitted parameters in their unit.
#   plots.sh        (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
set -uo pipefail
PYTHON=/usr/bin/python3
scripts="$BAPD_SOURCE_DIR/scripts"
work="validation_plots"
rm -rf "$work" && mkdir -p "$work" || exit 1
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }
run() { # name, options...
  local name="$1"; shift
  timeout 300 mpiexec -n 1 --oversubscribe --bind-to none "$BAPD_EXE" -options_file_yaml "$BAPD_SOURCE_DIR/tests/data/scenes/tiny.yaml" \
    -output_fields -output_fields_interval 25 "$@" -output_dir "$work/$name" > "$work/$name.log" 2>&1 ||
    { tail -20 "$work/$name.log"; echo "FAIL: $name did not run"; exit 1; }
}

(cd "$scripts" && $PYTHON -m doctest plot_labels.py) && echo "ok   plot_labels.py examples" || fail "plot_labels.py doctest"

run tiny
out="$($PYTHON "$scripts/plot_history.py" "$work/tiny" --x time_s --output "$work/history.png")" || fail "plot_history.py: $out"
echo "$out"
echo "$out" | grep -Eq ": top nominal stress \((Pa|kPa)\) against time \((s|ms)\), 1 run" || fail "plot_history.py axis labels: $out"
# a reference in kPa up to 27.5 kPa (bapd-fit's example data, '#' lines first) sets the axis's unit with the run's < 1 kPa
out="$($PYTHON "$scripts/plot_history.py" "$work/tiny" --reference eq36 --output "$work/reference.png" \
        --reference-csv "$BAPD_SOURCE_DIR/examples/calibration/pure_shear_data.csv:stretch,nominal_stress_kPa")" ||
  fail "plot_history.py --reference-csv: $out"
echo "$out"
echo "$out" | grep -q ": top nominal stress (kPa) against applied stretch λ (-), 1 run" || fail "plot_history.py with a reference: $out"

# check_grips RUN_DIR EXPECT_RIGHT(yes|no) plot_fields options...: the grip points and the colour scale
check_grips() {
  local dir="$1" expect="$2"; shift 2
  local line; line="$($PYTHON "$scripts/plot_fields.py" "$dir" --field cauchy_stress --component yy "$@")" || { fail "plot_fields.py $*: $line"; return; }
  echo "$line"
  $PYTHON - "$dir" "$line" "$expect" << 'EOF' || fail "plot_fields.py $* on $dir"
import glob, re, sys
import h5py, numpy as np
run, line, expect = sys.argv[1:]
path = sorted(glob.glob(f"{run}/fields/step_*.h5"))[-1]
with h5py.File(path, "r") as f:
    x = f["reference_position"][()]
    syy = f["cauchy_stress"][()][:, 4]
    step = int(f.attrs["step"])
outside = (x[:, 0] < 0) | (x[:, 0] > 0.01) | (x[:, 1] < 0) | (x[:, 1] > 0.01)  # the scene's 10 mm x 10 mm specimen
m = re.search(r"(\S+\.png): .* colour scale (\S+) to (\S+) (k?Pa); (\d+) grip points apart", line)
if not m:
    sys.exit(f"no colour scale and grip count in: {line}")
png, low, high, unit, grips = m.group(1), float(m.group(2)), float(m.group(3)), m.group(4), int(m.group(5))
right = grips == outside.sum()
print(f"  {grips} grip points drawn apart, {outside.sum()} outside the specimen; colour scale {low:.6g} to {high:.6g} {unit}")
if right != (expect == "yes"):
    sys.exit(f"grip points {grips}, outside the specimen {outside.sum()}: expected them {'equal' if expect == 'yes' else 'different'}")
if expect == "yes":
    scale = 1e3 if unit == "kPa" else 1.0
    specimen = syy[~outside]
    for got, want in ((low * scale, specimen.min()), (high * scale, specimen.max())):
        if abs(got - want) > 1e-5 * max(abs(specimen).max(), 1e-300):  # %.6g printed
            sys.exit(f"colour scale {low} to {high} {unit}, the specimen's sigma_yy spans {specimen.min()} to {specimen.max()} Pa")
    if abs(syy[outside]).max() <= abs(specimen).max() and syy[outside].min() >= specimen.min():
        print("  (the grips' stress lies within the specimen's here: the scale would not show the difference)")
    if not png.endswith(f"cauchy_stress_yy_step{step}.png"):
        sys.exit(f"{png}: the file name lacks the component (cauchy_stress_yy_step{step}.png)")
EOF
}
check_grips "$work/tiny" yes
run uneven -load_top_layers 3
check_grips "$work/uneven" yes # the files' load_set dataset names the grip points
# Files without load_set (an older bapd's): the mirrored guess is wrong, --specimen right.
cp -r "$work/uneven" "$work/uneven_old"
$PYTHON -c 'import glob, h5py, sys
for path in glob.glob(sys.argv[1] + "/fields/step_*.h5"):
    with h5py.File(path, "r+") as f:
        del f["load_set"]' "$work/uneven_old" || fail "removing load_set from the copied field files"
check_grips "$work/uneven_old" no
check_grips "$work/uneven_old" yes --specimen 0.01 0.01

# plot_fit.py: the legend names each law with its fitted parameters in their unit
fit="$(dirname "$BAPD_EXE")/bapd-fit"
if "$fit" -law neo_hookean -output_dir "$work/fit" -fit_gauge_length 0.02 -fit_cross_section 1e-5 \
     "uniaxial:$BAPD_SOURCE_DIR/tests/data/fit/uniaxial_comma_units.csv" > "$work/fit.log" 2>&1 &&
   [ -s "$work/fit/fit_uniaxial.png" ]; then
  here="$(pwd)"
  label="$(cd "$scripts" && $PYTHON -c "import plot_fit, sys; print(plot_fit.law_label(sys.argv[1], 'neo_hookean'))" "$here/$work/fit")"
  echo "$label" | grep -Eq "^neo_hookean: mu = [0-9.]+ kPa$" && echo "ok   plot_fit.py legend: $label" || fail "plot_fit.py legend: $label"
else fail "bapd-fit with its plot: $(cat "$work/fit.log")"; fi
exit $((failures > 0))
