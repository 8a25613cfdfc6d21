#!/usr/bin/env bash
# Short versions of paper scenes 1 and 2, a few seconds each, checking the
# figure each scene is about against a band that the full runs justify
# (docs/validation.md; the notched scene has its own test, notched_short.sh).
#   scenes_short.sh        (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
set -uo pipefail
work="validation_scenes_short"
rm -rf "$work" && mkdir -p "$work" || exit 1
ex="$BAPD_SOURCE_DIR/examples"
run() { # name, options...
  local name="$1"; shift
  timeout 300 mpiexec -n 1 --oversubscribe --bind-to none "$BAPD_EXE" "$@" -output_dir "$work/$name" > "$work/$name.log" 2>&1 ||
    { tail -20 "$work/$name.log"; echo "FAIL: $name did not run to the end"; exit 1; }
}
# Scene 1 at dx = 2 mm by the fast route (3 120 points, ~640 steps).
run plate -options_file_yaml "$ex/plate_hole.yaml" -options_file_yaml "$ex/plate_hole_fast.yaml" -body_dx 0.002
# Scene 2 at dx = 1 mm (700 points) to stretch 3 at the full run's loading rate.
run pure_shear -options_file_yaml "$ex/pure_shear.yaml" -body_dx 0.001 -load_schedule 0,1,0.5,3.0 -output_interval 20
/usr/bin/python3 - "$work" <<'PY'
import csv, sys
work = sys.argv[1]
failures = []
# Plate, with the defaults (grips outside the specimen, affine field, energy-consistent
# force): the runs converge on the FEA u_max from below (3.015 dx: -0.5 / -1.0 / -1.4 %
# at stretch 1.5 / 1.75 / 2 at dx = 2 mm, this run; -0.0 / -0.3 / -0.5 % at dx = 1 mm;
# docs/validation.md). At dx = 2 mm every static u_max must be 0.1 to 2 % below FEA;
# the paper's method (one rigid row inside, uncorrected bond-only force: -3.4 % here)
# fails this band, and so would a solution above the FEA.
FEA = {1.5: 8.62, 1.75: 11.10, 2.0: 13.01}
rows = list(csv.DictReader(open(f"{work}/plate/static_states.csv")))
seen = set()
for r in rows:
    lam = round(float(r["stretch"]), 2)
    if lam not in FEA:
        continue
    seen.add(lam)
    u = abs(float(r["left_mid_ux_m"])) * 1e3
    err = 100 * (u - FEA[lam]) / FEA[lam]
    print(f"plate, stretch {lam}: u_max {u:.4f} mm, {err:+.2f} % against FEA {FEA[lam]} mm")
    if not -2.0 <= err <= -0.1:
        failures.append(f"plate u_max at stretch {lam} is {err:+.2f} % off FEA, outside [-2.0, -0.1] %")
if seen != set(FEA):
    failures.append(f"plate: static states at {sorted(seen)}, expected {sorted(FEA)}")
# Pure shear: with the defaults the static states are within 0.4 % of the FE solution
# of the clamped sheet at dx = 0.5 and 1 mm, which lies 0.3 to 0.5 % below eq 36 (the
# free side edges); this run (dx = 1 mm, loaded in 0.5 s) measures 0.985 to 0.996 of
# eq 36 between stretch 1.5 and 3. Band: 0.975 to 1.01; the uncorrected bond-only
# force (0.95-0.96 at stretch 1.5) fails it.
MU, JM = 4.55e3, 162.6
def eq36(l):
    return MU * JM * (l - l ** -3) / (JM - l ** 2 - l ** -2 + 2)
rows = list(csv.DictReader(open(f"{work}/pure_shear/history.csv")))
for target in (1.5, 2.0, 2.5, 3.0):
    r = min(rows, key=lambda r: abs(float(r["stretch"]) - target))
    lam, s = float(r["stretch"]), float(r["top_nominal_stress_Pa"])
    ratio = s / eq36(lam)
    print(f"pure shear, stretch {lam:.3f}: {s / 1e3:.3f} kPa, eq 36 {eq36(lam) / 1e3:.3f} kPa, ratio {ratio:.4f}")
    if not 0.975 <= ratio <= 1.01:
        failures.append(f"pure shear at stretch {lam:.3f}: {ratio:.4f} of eq 36, outside [0.975, 1.01]")
for f in failures:
    print("FAIL", f)
sys.exit(1 if failures else 0)
PY
