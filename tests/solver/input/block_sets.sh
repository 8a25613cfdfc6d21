#!/usr/bin/env bash
# Block ids of a point cloud as load sets (-load_NAME_region block, scene_loading.cpp)
# and probes (-probe_NAME_block, scene_probes.cpp): a 20 x 20 cloud whose top two rows
# are block 2, bottom two rows block 3 and one point, (5.25, 5.25) mm, block 5, gripped
# and probed by block, must run exactly as the same cloud gripped by boxes around those
# rows and probed at that position (the same history and probe line, bit for bit), and
# the summary must count 40 points in each block set; on 2 ranks the history must be
# the same bits.
# Blocks 2 and 3 are not where a block-blind selection would look: block 1 (the rest)
# is given first in the file, and the two blocks are not contiguous in it.
#   block_sets.sh        (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
set -euo pipefail
work="input_block_sets"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
awk 'BEGIN { print "x,y,volume,block_id"
  for (j = 2; j < 18; j++) for (i = 0; i < 20; i++)
    printf "%.17g,%.17g,2.5e-10,%d\n", (i + 0.5) * 0.0005, (j + 0.5) * 0.0005, i == 10 && j == 10 ? 5 : 1
  for (j = 0; j < 20; j++) if (j < 2 || j >= 18) for (i = 0; i < 20; i++)
    printf "%.17g,%.17g,2.5e-10,%d\n", (i + 0.5) * 0.0005, (j + 0.5) * 0.0005, j < 2 ? 3 : 2 }' > cloud.csv
scene=(-options_file_yaml "$BAPD_SOURCE_DIR/tests/data/scenes/cloud.yaml" -body_cloud cloud.csv -progress_interval 100000)
"$BAPD_EXE" "${scene[@]}" -load_top_region block -load_top_block 2 -load_bottom_region block -load_bottom_block 3 \
  -probes p -probe_p_block 5 -output_dir by_block > by_block.log 2>&1 || { cat by_block.log; exit 1; }
"$BAPD_EXE" "${scene[@]}" -load_top_region box -load_top_box 0,0.009,0.01,0.01 -load_bottom_region box -load_bottom_box 0,0,0.01,0.001 \
  -probes p -probe_p_at 0.00525,0.00525 -output_dir by_box > by_box.log 2>&1 || { cat by_box.log; exit 1; }
for s in "top: block 2 of the cloud (40 points)" "bottom: block 3 of the cloud (40 points)"; do
  grep -qF "$s" by_block.log || { echo "FAIL: no '$s' in the summary"; grep "load set" by_block.log; exit 1; }
done
line=$(grep "^Probe p:" by_block.log) || { echo "FAIL: no probe line"; cat by_block.log; exit 1; }
[ "$line" = "$(grep "^Probe p:" by_box.log)" ] || { echo "FAIL: '$line' against '$(grep "^Probe p:" by_box.log)'"; exit 1; }
case "$line" in *"(0.00525, 0.00525) m"*) ;; *) echo "FAIL: '$line' is not the point at (0.00525, 0.00525) m"; exit 1 ;; esac
cmp by_block/history.csv by_box/history.csv
# The points are found by their coordinates: the same on any rank count (tolerance 0).
OMPI_MCA_rmaps_base_oversubscribe=1 "$BAPD_SOURCE_DIR/run_mpi.sh" -n 2 "${scene[@]:1}" -load_top_region block -load_top_block 2 \
  -load_bottom_region block -load_bottom_block 3 -probes p -probe_p_block 5 -output_dir by_block_np2 > by_block_np2.log 2>&1 ||
  { cat by_block_np2.log; exit 1; }
cmp by_block/history.csv by_block_np2/history.csv
echo "ok: grips and a probe by block id give the history of boxes and a position"
