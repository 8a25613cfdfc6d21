#!/usr/bin/env bash
# The field output opens in a real ParaView (Debian's python3-paraview, installed by
# scripts/install-deps.sh --tests), with the reader it picks by default (Xdmf3ReaderS) and
# with the README's "Xdmf Reader": every point drawn as a cell, the arrays, the run
# state as field data, every output time, a damage picture with the points in it
# (open_fields.py). A notched sheet on 2 ranks whose crack has run, once drawn at the
# current positions and once at the reference ones (-output_fields_geometry).
set -euo pipefail
source "$BAPD_SOURCE_DIR/tests/mpi/restart/common.sh"
if ! command -v pvpython > /dev/null || ! command -v xvfb-run > /dev/null; then
  echo "SKIPPED: pvpython or xvfb-run is missing: run scripts/install-deps.sh --tests (python3-paraview, xvfb)"
  exit 77
fi
work="paraview_fields"
rm -rf "$work"; mkdir -p "$work"
# 30 x 12 points and 6 grip rows outside above and below (720 points), 390 steps: the crack runs
# from about step 150; files at 0, 100, 200, 300, 390.
scene=("${NOTCHED[@]}" "${FRACTURE[@]}" -body_dx 0.001 -end_step 390 -output_fields -output_fields_interval 100)
run 2 "$work/current" "${scene[@]}"
run 2 "$work/reference" "${scene[@]}" -output_fields_geometry reference

# ParaView under a virtual X server. -noreset: Xvfb otherwise resets when pvpython's
# first, short-lived X connection closes, and the render window then finds no server.
pv() {
  xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" pvpython "$BAPD_SOURCE_DIR/tests/validation/paraview/open_fields.py" "$@" 2>&1 |
    grep -v '^\s*[0-9]\+\s\+0x' # (a crash's stack trace: its first lines say what failed)
  return "${PIPESTATUS[0]}"
}
for geometry in current reference; do
  pv "$work/$geometry" 720 5 "$work" --last-step 390 --ranks 2 --geometry "$geometry" ||
    fail "ParaView does not show the fields of $work/$geometry as expected"
done
for png in "$work"/damage_*.png; do
  [ "$(head -c 8 "$png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "$png is not a PNG"
done
echo "ParaView: both readers draw every point with its arrays and run state, at the current and the reference positions"
