#!/usr/bin/env bash
# Grips that do not distort the sheet: a small pure-shear sheet (30 mm x
# 10 mm free region, dx = 1 mm) clamped by grips outside it, brought to static states
# at stretch 1.5 and 2 by the fast route, with the defaults (grips two horizons deep,
# affine field, energy-consistent force), and with the tensor-corrected bond-only
# force (-force_form bond_only, whose auto correction is tensor). It checks that
# - the nominal stress does not depend on the grip's depth: 2 horizons (6 rows) and
#   3 horizons (9 rows, where no free point's force reads anything the grip's outer
#   edge touches) agree within 0.5 %;
# - no free row next to a grip is stretched more than 3 % above the bulk (the gap
#   from the grip's inner row to the first free row, and the next two, at x = 15 mm);
# - the corrected bond-only form with the default grips meets both marks too (its
#   stress within 0.5 % of the deep grips' energy-consistent one);
# and, so that both checks can fail, that grips one horizon deep (3 rows: the free
# sheet's neighbours then see the grip's outer edge) miss both marks.
#   grips_short.sh        (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
set -uo pipefail
work="validation_grips_short"
rm -rf "$work" && mkdir -p "$work" || exit 1
run() { # name, options...
  local name="$1"; shift
  timeout 300 mpiexec -n 1 --oversubscribe --bind-to none "$BAPD_EXE" -options_file_yaml "$BAPD_SOURCE_DIR/examples/pure_shear.yaml" \
    -body_width 0.030 -body_dx 0.001 -probe_right_mid_at 0.030,0.005 -load_schedule 0,1,0.05,1.5,1.05,1.5,1.1,2,2.1,2 \
    -relaxation adaptive -static_tolerance 1e-10 -output_interval 20 -output_final_state "$@" -output_dir "$work/$name" \
    > "$work/$name.log" 2>&1 || { tail -20 "$work/$name.log"; echo "FAIL: $name did not run to the end"; exit 1; }
}
run two_horizons
run three_horizons -load_top_layers 9 -load_bottom_layers 9
run one_horizon -load_top_layers 3 -load_bottom_layers 3
run bond_only -force_form bond_only
/usr/bin/python3 - "$work" <<'PY'
import csv, sys
import numpy as np
work = sys.argv[1]
AREA = 0.030 * 0.003

def stresses(name):
    rows = list(csv.DictReader(open(f"{work}/{name}/static_states.csv")))
    return {round(float(r["stretch"]), 2): float(r["top_reaction_y_N"]) / AREA for r in rows}

def worst_gap(name):
    """Largest relative excess of the 3 row gaps next to each grip over the bulk gap
    (column at x = 15 mm, final state at stretch 2)."""
    s = np.loadtxt(f"{work}/{name}/final_state.csv", delimiter=",", skiprows=1)
    col = np.abs(s[:, 1] - 0.0145) < 1e-9
    y, yy = s[col, 2], s[col, 2] + s[col, 4]
    order = np.argsort(y)
    y, gaps = y[order], np.diff(yy[order])
    bulk = gaps[np.argmin(np.abs(y[:-1] - 0.0045))]
    bottom = np.nonzero((y[:-1] < 0) & (y[1:] > 0))[0][0]
    top = np.nonzero((y[:-1] < 0.010) & (y[1:] > 0.010))[0][0]
    near = list(gaps[bottom:bottom + 3]) + list(gaps[top - 2:top + 1])
    return max(g / bulk - 1 for g in near)

failures = []
deep, two, one, bond = (stresses(n) for n in ("three_horizons", "two_horizons", "one_horizon", "bond_only"))
for lam in (1.5, 2.0):
    d2, d1, db = two[lam] / deep[lam] - 1, one[lam] / deep[lam] - 1, bond[lam] / deep[lam] - 1
    print(f"stretch {lam}: 3 horizons {deep[lam]:.1f} Pa; 2 horizons {100 * d2:+.2f} %, 1 horizon {100 * d1:+.2f} %, "
          f"bond-only (tensor) 2 horizons {100 * db:+.2f} %")
    if abs(d2) > 0.005:  # the bound for grips of different depths
        failures.append(f"stretch {lam}: grips 2 and 3 horizons deep differ by {100 * d2:+.2f} % (> 0.5 %)")
    if abs(db) > 0.005:
        failures.append(f"stretch {lam}: the corrected bond-only form is {100 * db:+.2f} % off the energy-consistent one (> 0.5 %)")
    if abs(d1) <= 0.005:
        failures.append(f"stretch {lam}: grips 1 horizon deep agree within 0.5 %: the check would not see a grip's depth")
for name, should_pass in (("two_horizons", True), ("three_horizons", True), ("one_horizon", False), ("bond_only", True)):
    g = worst_gap(name)
    print(f"{name}: largest row gap next to a grip {100 * g:+.2f} % over the bulk")
    if should_pass and g > 0.03:
        failures.append(f"{name}: a free row next to a grip is stretched {100 * g:.2f} % above the bulk (> 3 %)")
    if not should_pass and g <= 0.03:
        failures.append(f"{name}: its rows next to the grips are within 3 % of the bulk: the check would not see a shallow grip")
for f in failures:
    print("FAIL", f)
sys.exit(1 if failures else 0)
PY
