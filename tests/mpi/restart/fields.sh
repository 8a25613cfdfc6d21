#!/usr/bin/env bash
# The field output opens in a real reader: h5py reads the XDMF index and every file it
# names, and finds the lattice, zero motion at t = 0, damage in [0, 1] and a crack at
# the end (check_fields.py). The files do not depend on the rank layout (1 rank vs 3,
# bit for bit), and scripts/plot_fields.py renders one to PNG.
set -euo pipefail
source "$BAPD_SOURCE_DIR/tests/mpi/restart/common.sh"
work="restart_fields"
rm -rf "$work"; mkdir -p "$work"
# 30 x 12 points and 6 grip rows outside above and below (the default), 400 steps: the crack runs from about step 150.
scene=("${NOTCHED[@]}" "${FRACTURE[@]}" -body_dx 0.001 -end_step 390 -output_fields -output_fields_interval 50)
run 3 "$work/np3" "${scene[@]}"
run 1 "$work/np1" "${scene[@]}"
$PYTHON "$BAPD_SOURCE_DIR/tests/mpi/restart/check_fields.py" --dx 0.001 --nx 30 --ny 12 --grip_rows 6 --interval 50 --last 390 --thickness 0.003 --ranks 3 \
  "$work/np3/fields.xdmf"
for f in "$work"/np3/fields/*.h5; do
  $PYTHON "$BAPD_SOURCE_DIR/tests/mpi/restart/compare_fields.py" --tolerance 0 "$f" "$work/np1/fields/$(basename "$f")"
done
$PYTHON "$BAPD_SOURCE_DIR/scripts/plot_fields.py" "$work/np3" --field damage --time 1 --output "$work/damage.png"
$PYTHON "$BAPD_SOURCE_DIR/scripts/plot_fields.py" "$work/np3/fields.xdmf" --field displacement --component y --step 200 \
  --output "$work/uy.png"
for png in damage uy; do
  [ "$(head -c 8 "$work/$png.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "$png.png is not a PNG"
done
echo "field output: read back, layout independent, plotted"
