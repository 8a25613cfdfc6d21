#!/usr/bin/env bash
# The 3D block with a cylindrical hole against the dolfinx solution.
# examples/block_hole_3d.yaml as shipped (dx = 0.5 mm, 7 680 points, the energy-consistent
# form, its tabs gripped with the affine field: the outside treatment; the fast static
# route) to its static state at stretch 1.25 (the example's second level, 1.5, would
# double the time: it is in the table), at K = 10 mu, 2 ranks, against the Taylor-Hood
# P2-P1 solution of scripts/fe/block_hole_3d.py at the same K, read from
# tests/data/fe/block_hole_3d_K10.json (s: the finest mesh; each probe: the FE displacement at
# the lattice point the probe reads, "lattice" -> "0.5"). The convergence table
# (docs/validation_3d.md section 7.2, dx = 1, 0.5, 0.25 mm, both forms, rigid and affine
# tabs) says what holds at this spacing:
# ASSERTED - the nominal stress s within 1 % (measured +0.07 %) and
# the crown probe (crown_mid uy) within 3 % (+2.47 %);
# PRINTED, not asserted - side_mid ux and the probes next to the hole (ligament_mid ux,
# ligament_face ux and uz): +4 to +18 % at this spacing, half that at 0.25 mm.
# Also asserted: each probe reads the lattice point the JSON's value is for.
# Any further argument goes to bapd (after the scene's options): the check fails with
# the tabs rigid (-load_grip_field rigid: s -5.32 %), with a softer material
# (-material_mu 4.3e3) or with the bond-only form (-force_form bond_only: s +3.97 %).
#   block_hole_3d_short.sh [bapd options]    (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
set -euo pipefail
source "$BAPD_SOURCE_DIR/tests/mpi/restart/common.sh" # run, fail, PYTHON
work="validation_block_hole_3d_short"
rm -rf "$work"; mkdir -p "$work"
run 2 "$work/pd" -options_file_yaml "$BAPD_SOURCE_DIR/examples/block_hole_3d.yaml" \
    -material_bulk_ratio 10 -material_volumetric bond -load_schedule 0,1.0,0.025,1.25,1.025,1.25 \
    -progress_interval 1000000 "$@"
$PYTHON - "$work" "$BAPD_SOURCE_DIR/tests/data/fe/block_hole_3d_K10.json" <<'PY'
import csv, json, re, sys
work, fe_path = sys.argv[1], sys.argv[2]
fe = json.load(open(fe_path))
lattice = fe["lattice"]["0.5"]
AREA = 0.010 * 0.004                       # m^2: the FE's s is top reaction / (10 mm x 4 mm)
TOL = 0.03                                 # the asserted probe, crown_mid uy: +2.47 % measured
TOL_S = 0.01                               # s: +0.07 % measured
# (name, probe, component index, column suffix, asserted)
CHECKS = [("side_mid ux", "side_mid", 0, "ux", False),
          ("ligament_mid ux", "ligament_mid", 0, "ux", False),
          ("ligament_face ux", "ligament_face", 0, "ux", False),
          ("ligament_face uz", "ligament_face", 2, "uz", False),
          ("crown_mid uy", "crown_mid", 1, "uy", True)]
ok = True
# The probes must read the points the FE values are for (the JSON's lattice points).
log = open(f"{work}/pd.log").read()
for probe, entry in lattice.items():
    m = re.search(rf"Probe {probe}: point \d+ at \(([^)]*)\) m", log)
    at = [1e3 * float(v) for v in m.group(1).split(",")] if m else None
    if at is None or max(abs(a - b) for a, b in zip(at, entry["point_mm"])) > 1e-9:
        print(f"probe {probe} reads {at} mm, the FE value is for {entry['point_mm']} mm")
        ok = False
states = {f"{float(r['stretch']):g}": r for r in csv.DictReader(open(f"{work}/pd/static_states.csv"))}
for lam in ("1.25",):
    if lam not in states:
        sys.exit(f"FAILED: no static state at stretch {lam}")
    r = states[lam]
    s = float(r["top_reaction_y_N"]) / AREA / 1e3
    s_fe = fe["values"][f"s_{lam}"]["finest"]
    rel = s / s_fe - 1
    ok &= abs(rel) <= TOL_S
    print(f"lambda {lam}: s {s:.4f} kPa, FE {s_fe:.4f}, {100 * rel:+.2f} % (tolerance {100 * TOL_S:g} %)")
    for name, probe, c, col, asserted in CHECKS:
        u = 1e3 * float(r[f"{probe}_{col}_m"])
        u_fe = lattice[probe]["u_mm"][lam][c]
        rel = u / u_fe - 1
        note = f"(tolerance {100 * TOL:g} %)" if asserted else "(not asserted)"
        print(f"lambda {lam}: {name} {u:.4f} mm, FE {u_fe:.4f}, {100 * rel:+.2f} % {note}")
        if asserted:
            ok &= abs(rel) <= TOL
sys.exit(0 if ok else "FAILED: the block's s is not within 1 % or its crown probe not within 3 % of the FE")
PY
echo "block_hole_3d_short: s within 1 % and the crown probe within 3 % of the FE"
