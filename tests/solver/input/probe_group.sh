#!/usr/bin/env bash
# A probe placed by a Gmsh physical point (-probe_NAME_group, scene_probes.cpp) reads
# the same material point as one placed by its coordinates (-probe_NAME_at): the same
# probe line and the same probe columns in history.csv, bit for bit.
#   probe_group.sh        (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
set -euo pipefail
work="input_probe_group"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
geo="$BAPD_SOURCE_DIR/tests/data/geometry/probe_point.geo"
scene=(-options_file_yaml "$BAPD_SOURCE_DIR/tests/data/scenes/tiny.yaml" -body_shapes sq -body_sq_type mesh -body_sq_op intersect
       -body_sq_file "$geo" -probes p -progress_interval 100000)
"$BAPD_EXE" "${scene[@]}" -probe_p_group gauge -output_dir by_group > by_group.log 2>&1 || { cat by_group.log; exit 1; }
"$BAPD_EXE" "${scene[@]}" -probe_p_at 0.0071,0.0033 -output_dir by_at > by_at.log 2>&1 || { cat by_at.log; exit 1; }
line=$(grep "^Probe p:" by_group.log) || { echo "FAIL: no probe line"; cat by_group.log; exit 1; }
[ "$line" = "$(grep "^Probe p:" by_at.log)" ] || { echo "FAIL: '$line' against '$(grep "^Probe p:" by_at.log)'"; exit 1; }
# The nearest lattice point to (7.1, 3.3) mm on the 0.5 mm cell-centred grid: (7.25, 3.25) mm.
case "$line" in *"(0.00725, 0.00325) m"*) ;; *) echo "FAIL: '$line' is not the point at (0.00725, 0.00325) m"; exit 1 ;; esac
cmp by_group/history.csv by_at/history.csv
echo "ok   $line, history identical"
