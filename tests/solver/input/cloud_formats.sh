#!/usr/bin/env bash
# One point cloud in three files (point_cloud_file.hpp): CSV with a header, Peridigm's
# text format ("# x y z block_id volume", blanks, its column order) and HDF5 (/x, /y,
# /volume, /block_id). The same scene on each must give the same final state, bit for bit.
#   cloud_formats.sh        (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
set -euo pipefail
work="input_cloud_formats"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
csv="$BAPD_SOURCE_DIR/examples/geometry/graded_sheet.csv"
/usr/bin/python3 - "$csv" <<'PY'
import sys
import h5py
import numpy as np
rows = np.loadtxt(sys.argv[1], delimiter=",", skiprows=1)  # x, y, volume, block_id
with open("peridigm.txt", "w") as f:
    f.write("# x y z block_id volume\n")
    for x, y, v, b in rows:
        f.write(f"{x!r} {y!r} 0.0 {int(b)} {v!r}\n")
with h5py.File("cloud.h5", "w") as f:
    for k, name in enumerate(["x", "y", "volume", "block_id"]):
        f.create_dataset(name, data=rows[:, k])
PY
for form in "$csv" peridigm.txt cloud.h5; do
  name=$(basename "$form" | tr . _)
  "$BAPD_EXE" -options_file_yaml "$BAPD_SOURCE_DIR/examples/point_cloud.yaml" -body_cloud "$form" \
    -load_schedule 0,1,0.01,1.05 -output_dir "$name" -progress_interval 100000 > "$name.log" 2>&1 || { cat "$name.log"; exit 1; }
  grep -q "^Body: 1376 points" "$name.log" || { echo "FAIL $form: not the 1376 points of the cloud"; grep "^Body" "$name.log"; exit 1; }
done
cmp graded_sheet_csv/final_state.csv peridigm_txt/final_state.csv
cmp graded_sheet_csv/final_state.csv cloud_h5/final_state.csv
echo "ok: CSV, Peridigm text and HDF5 give the same final state"
