#!/usr/bin/env bash
# The 3D crack, short: examples/notched_block_3d.yaml (30 x 10 x 4 mm at dx = 1 mm, a
# through-thickness notch in the plane y = 5 mm from x = 20 mm to the face x = 30 mm),
# at K = 10 mu (a shorter stable step) with a low critical stretch (1.5) and a ramp to 2.5
# over 0.2 s, run 350 steps (far stretch 1.42), so that the crack starts at the notch tip
# and runs along its plane. Checks, tolerance 0 where the docs say bit for bit:
#  - history.csv, final_state.csv and broken_bonds.csv identical on 1 and 2 ranks;
#  - bonds broke at the notch tip (a midpoint within a horizon of the tip line x = 20,
#    y = 5 mm);
#  - the crack is the notch's: at least 75 % of the broken bonds have their midpoint
#    within 1.5 mm of the plane y = 5 mm (measured 90.2 %, 1 309 bonds broken; the rest are at the
#    corners where the free side x = 0 meets the rigid tabs, a stress concentration of
#    the coarse block that breaks a few bonds at the same far stretch as the tip), and it
#    has grown from the tip: bonds on that plane broke at x < 17 mm (a horizon ahead of the
#    tip; measured down to x = 14.5 mm);
#  - the field file holds a damage dataset, nonzero.
# docs/validation_3d.md section 7.3 has the full example.
#   notched_block_3d_short.sh        (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
set -euo pipefail
source "$BAPD_SOURCE_DIR/tests/mpi/restart/common.sh" # run, fail, history_column, PYTHON
work="validation_notched_block_3d_short"
rm -rf "$work"; mkdir -p "$work"
steps=350
scene=(-options_file_yaml "$BAPD_SOURCE_DIR/examples/notched_block_3d.yaml"
       -material_bulk_ratio 10 -failure_critical_stretch 1.5 -load_schedule 0,1,0.2,2.5
       -end_step $steps -output_interval 20 -progress_interval 1000000 -output_final_state
       -output_fields -output_fields_interval $steps)
# Both runs at once, so that the two cores the test holds (PROCESSORS 2) are busy for
# its whole length, not one of them idle while the 1-rank run goes alone. (run exits
# its subshell on a failure.)
run 1 "$work/np1" "${scene[@]}" &
pid1=$!
run 2 "$work/np2" "${scene[@]}" &
pid2=$!
wait $pid1 || { wait $pid2; exit 1; }
wait $pid2 || exit 1
$PYTHON "$BAPD_SOURCE_DIR/tests/mpi/compare_runs.py" --tolerance 0 --expect-broken "$work/np1" "$work/np2"
cmp -s "$work/np1/broken_bonds.csv" "$work/np2/broken_bonds.csv" || fail "broken_bonds.csv differs byte for byte"
echo "broken bonds at step $steps: $(history_column "$work/np1" $steps broken_bonds)"
$PYTHON - "$work/np1" $steps <<'PY'
import csv, sys, h5py, numpy as np
d, steps = sys.argv[1], int(sys.argv[2])
pos = {int(r["natural_id"]): (float(r["x_m"]), float(r["y_m"]), float(r["z_m"]))
       for r in csv.DictReader(open(f"{d}/final_state.csv"))}
delta = 3.015e-3
bonds = [tuple(int(v) for v in r) for r in list(csv.reader(open(f"{d}/broken_bonds.csv")))[1:]]
mid = np.array([[(pos[i][k] + pos[j][k]) / 2 for k in range(3)] for i, j in bonds])
print(f"{len(bonds)} broken (directed) pairs; midpoints x in [{mid[:,0].min()*1e3:.2f}, {mid[:,0].max()*1e3:.2f}] mm, "
      f"y in [{mid[:,1].min()*1e3:.2f}, {mid[:,1].max()*1e3:.2f}] mm")
tip = np.hypot(mid[:, 0] - 0.020, mid[:, 1] - 0.005) <= delta
plane = np.abs(mid[:, 1] - 0.005) <= 1.5e-3
ahead = plane & (mid[:, 0] < 0.020 - delta)
print(f"at the tip: {tip.sum()}; on the notch plane: {plane.sum()} ({100 * plane.mean():.1f} %), "
      f"of them {ahead.sum()} more than a horizon ahead of the tip (x down to {mid[plane, 0].min() * 1e3:.2f} mm)")
if not tip.any():
    sys.exit("FAILED: no bond broke at the notch tip")
if plane.mean() < 0.75:
    sys.exit("FAILED: fewer than 75 % of the broken bonds lie on the notch plane")
if not ahead.any():
    sys.exit("FAILED: the crack did not grow from the notch tip along its plane")
with h5py.File(f"{d}/fields/step_{steps:08d}.h5") as f:
    names = []
    f.visit(names.append)
    dam = [n for n in names if n.split("/")[-1] == "damage"]
    if not dam:
        sys.exit(f"FAILED: no damage dataset in the field file: {names}")
    damage = np.asarray(f[dam[0]]).ravel()
    print(f"damage: {dam[0]}, max {damage.max():.3f}, {np.count_nonzero(damage)} points damaged")
    if damage.max() <= 0:
        sys.exit("FAILED: the damage field is zero everywhere")
PY
echo "notched_block_3d_short: identical on 1 and 2 ranks, the crack starts at the notch"
