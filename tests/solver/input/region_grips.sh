#!/usr/bin/env bash
# Grips on the body's own points with the outside treatment's equivalent
# (-load_grip_field affine for two region grips, Loading::SetAffineLevers): a 10 x 16 mm
# sheet gripped by its 3 mm end tabs (6 rows, two horizons: the depth of a default grip
# outside), as boxes and as Gmsh physical surfaces (tests/data/geometry/tabs.geo), must carry
# the force of the 10 x 10 mm sheet gripped outside by its edges (the default: 6 rows
# beyond each edge, affine). The points are the same (shifted by 3 mm), so the top
# grip's reaction must agree to round-off at every row of history.csv; the same tabs
# with the rigid field (the region default) must not (the test can tell the two apart).
# On 2 ranks the boxes must give the same bits as on 1.
#   region_grips.sh        (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
set -euo pipefail
work="input_region_grips"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
geo="$BAPD_SOURCE_DIR/tests/data/geometry/tabs.geo"
# A fixed step: the stable-step estimate (power iteration) differs in its last digits
# between the two point sets (2e-9 of dt), which would hide the comparison.
base=(-options_file_yaml "$BAPD_SOURCE_DIR/tests/data/scenes/tiny.yaml" -time_step 2e-4 -progress_interval 100000)
tabs=(-body_height 0.016 -load_reference_length 0.01)
run() { local name="$1"; shift; "$BAPD_EXE" "${base[@]}" "$@" -output_dir "$name" > "$name.log" 2>&1 || { cat "$name.log"; exit 1; }; }
run edges
run boxes "${tabs[@]}" -load_grip_field affine -load_top_region box -load_top_box 0,0.013,0.01,0.016 \
  -load_bottom_region box -load_bottom_box 0,0,0.01,0.003
run groups "${tabs[@]}" -load_grip_field affine -body_shapes s -body_s_type mesh -body_s_op intersect -body_s_file "$geo" \
  -load_top_region group -load_top_group grip_top -load_bottom_region group -load_bottom_group grip_bottom
# The grip lines come from an exact min over the ranks: the same bits on 2 ranks.
OMPI_MCA_rmaps_base_oversubscribe=1 "$BAPD_SOURCE_DIR/run_mpi.sh" -n 2 "${base[@]:1}" "${tabs[@]}" -load_grip_field affine \
  -load_top_region box -load_top_box 0,0.013,0.01,0.016 -load_bottom_region box -load_bottom_box 0,0,0.01,0.003 -output_dir boxes_np2 \
  > boxes_np2.log 2>&1 || { cat boxes_np2.log; exit 1; }
cmp boxes/history.csv boxes_np2/history.csv
run rigid "${tabs[@]}" -load_top_region box -load_top_box 0,0.013,0.01,0.016 -load_bottom_region box -load_bottom_box 0,0,0.01,0.003
grep -q "grip field affine" edges.log || { echo "FAIL: the edge grips are not affine"; grep schedule edges.log; exit 1; }
/usr/bin/python3 - <<'PY'
import csv, sys
def column(name):
    with open(f"{name}/history.csv") as f:
        return [float(r["top_reaction_y_N"]) for r in csv.DictReader(f)]
edges = column("edges")
scale = max(abs(v) for v in edges)
assert scale > 0, "no force on the top grip"
fails = 0
for name, close in (("boxes", True), ("groups", True), ("rigid", False)):
    other = column(name)
    assert len(other) == len(edges), f"{name}: {len(other)} rows against {len(edges)}"
    diff = max(abs(a - b) for a, b in zip(edges, other)) / scale
    print(f"{name:7s} top reaction against the edge grips outside: largest difference {diff:.3g} of the largest force")
    # Round-off of the 3 mm shift in the positions, grown over ~50 steps; the rigid
    # field changes the force by percents.
    if close and not diff < 1e-9: fails += 1; print(f"FAIL {name}: not the force of the edge grips outside")
    if not close and not diff > 1e-3: fails += 1; print(f"FAIL {name}: the rigid field gives the affine force")
sys.exit(1 if fails else 0)
PY
echo "ok: region grips (box and group) with the affine field carry the force of edge grips outside"
