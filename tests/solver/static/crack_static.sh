#!/usr/bin/env bash
# The static solver breaks bonds: on the notched pure-shear sheet (dx = 1 mm, 30 mm wide,
# 10 mm notch), pulled by the same schedule, the first bonds break within 1 % of the
# strain (lambda - 1) of the dynamic run's first break, with the critical stretch and
# with the fracture energy. Onset: the stretch of the first history row with a broken
# bond (the dynamic run writes a row every step: 0.002 in stretch apart there; the static
# run locates its first break within -static_onset_tolerance, 1e-3 of the strain).
#   crack_static.sh        (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
. "$(dirname "$0")/common.sh" static_crack
notch=(-body_dx 0.001 -body_width 0.03 -body_notches 0.02,0.005,0.03,0.005 -probe_notch_mouth_top_at 0.03,0.0052
       -probe_notch_mouth_bottom_at 0.03,0.0048 -progress_interval 1000000)
# run NAME SCENE END_STRETCH OPTIONS...: the sheet to END_STRETCH at the scene's rate, 4 per second.
run() {
  local name="$1" scene="$2" end="$3"
  shift 3
  local time
  time=$(/usr/bin/python3 -c "print(($end - 1) / 4)")
  timeout 300 mpiexec -n 1 "$BAPD_EXE" -options_file_yaml "$src/examples/$scene" "${notch[@]}" -load_schedule "0,1,$time,$end" \
    -output_dir "$name" "$@" > "$name.log" 2>&1 || { fail "$name: exit $?"; tail -5 "$name.log"; }
}
# The critical stretch 7.2 (first break near stretch 2.51) and Gamma = 165 J/m^2 (2.74).
run stretch_dynamic notched_pure_shear.yaml 2.6 -output_interval 1
run stretch_static notched_pure_shear.yaml 2.6 -solver static
run energy_dynamic notched_pure_shear_gamma.yaml 2.8 -output_interval 1
run energy_static notched_pure_shear_gamma.yaml 2.8 -solver static
/usr/bin/python3 - <<'PY' || failures=$((failures + 1))
import csv
def onset(name):
    for r in csv.DictReader(open(f"{name}/history.csv")):
        if int(r["broken_bonds"]) > 0:
            return float(r["stretch"])
    return None
ok = True
for criterion in ("stretch", "energy"):
    dynamic, static = onset(f"{criterion}_dynamic"), onset(f"{criterion}_static")
    if dynamic is None or static is None:
        print(f"FAIL {criterion}: no bond broke (dynamic {dynamic}, static {static})")
        ok = False
        continue
    off = abs(static - dynamic) / (dynamic - 1)
    print(f"{criterion}: first break at stretch {static:.5f} static, {dynamic:.5f} dynamic: {off:.2%} of the strain apart")
    ok = ok and off < 0.01
raise SystemExit(0 if ok else 1)
PY
grep -q "bonds broken: .*the first at stretch" energy_static.log || fail "the static summary does not name the first break"
finish crack_static
