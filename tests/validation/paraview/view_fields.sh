#!/usr/bin/env bash
# scripts/view_fields.py opens a run's fields ready to look at, in a real ParaView
# (pvpython under Xvfb): on the notched sheet of fields.sh (720 points with the grips
# outside), once as written (current positions) and once from files written at the
# reference positions, it draws the points as spheres a point spacing wide, coloured
# by the default field (the displacement magnitude, or the von Mises stress where the
# files hold it) with the grips in grey, and by a tensor component, writes a PNG and a state file that
# ParaView loads back (check_view.py). Exit code 77 (pvpython missing) is a skip.
set -euo pipefail
source "$BAPD_SOURCE_DIR/tests/mpi/restart/common.sh"
if ! command -v pvpython > /dev/null || ! command -v xvfb-run > /dev/null; then
  echo "SKIPPED: pvpython or xvfb-run is missing: run scripts/install-deps.sh (python3-paraview, xvfb)"
  exit 77
fi
work="paraview_view_fields"
rm -rf "$work"; mkdir -p "$work"
scene=("${NOTCHED[@]}" "${FRACTURE[@]}" -body_dx 0.001 -end_step 200 -output_fields -output_fields_interval 100)
# Side by side, the two runs and then the three views below (each pvpython is mostly
# one core's work): the test holds two cores (PROCESSORS 2), which a sequence left half
# idle (side_by_side: common.sh).
run_current() { run 2 "$work/current" "${scene[@]}"; }
run_reference() { run 2 "$work/reference" "${scene[@]}" -output_fields_geometry reference; }
side_by_side run_current run_reference

# -noreset: Xvfb otherwise resets when pvpython's first, short-lived X connection
# closes, and the render window then finds no server (fields.sh).
pv() {
  xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" pvpython "$@" 2>&1 | grep -v '^\s*[0-9]\+\s\+0x'
  return "${PIPESTATUS[0]}"
}
view="$BAPD_SOURCE_DIR/scripts/view_fields.py"
check="$BAPD_SOURCE_DIR/tests/validation/paraview/check_view.py"
# view_default GEOMETRY: the default view of the run's fields, checked and loaded back.
view_default() {
  local geometry="$1"
  pv "$view" "$work/$geometry" --png "$work/$geometry.png" --state "$work/$geometry.pvsm" --resolution 600 450 \
    > "$work/$geometry.log" || fail "view_fields.py failed on $work/$geometry: $(cat "$work/$geometry.log")"
  grep -Eq "coloured by (displacement magnitude|von.mises)" "$work/$geometry.log" ||
    fail "the default colouring is neither the displacement magnitude nor a von Mises stress: $(cat "$work/$geometry.log")"
  grep -Eq "; [1-9][0-9]* grip points in grey" "$work/$geometry.log" ||
    fail "the grips (the files' load_set) are not drawn apart in grey: $(cat "$work/$geometry.log")"
  pv "$check" "$work/$geometry.png" "$work/$geometry.pvsm" "$work/$geometry" 720 200 > "$work/$geometry.check.log" ||
    fail "the view of $work/$geometry: $(cat "$work/$geometry.check.log")"
  cat "$work/$geometry.log" "$work/$geometry.check.log"
}
view_current() { view_default current; }
view_reference() { view_default reference; }
# A component at a time, and a bad request: one clear error, not a ParaView trace.
view_component() {
  pv "$view" "$work/current" --field cauchy_stress --component yy --time 0 --png "$work/syy_t0.png" --resolution 600 450 \
    > "$work/syy.log" || fail "view_fields.py --field cauchy_stress --component yy: $(cat "$work/syy.log")"
  grep -q "coloured by cauchy stress yy" "$work/syy.log" || fail "not coloured by the yy component: $(cat "$work/syy.log")"
  grep -q "t = 0 s" "$work/syy.log" || fail "--time 0 does not show the first output: $(cat "$work/syy.log")"
  cat "$work/syy.log"
  local out
  if out="$(pv "$view" "$work/current" --field cauchy_stress --component x --png "$work/bad.png")"; then
    fail "a vector component of a tensor was accepted"
  fi
  echo "$out" | grep -q "view_fields.py: error: cauchy_stress is a tensor" || fail "the error for --component x of a tensor: $out"
}
side_by_side view_current view_reference view_component
echo "view_fields.py: spheres at the deformed positions, coloured, PNG and a state file ParaView loads"
