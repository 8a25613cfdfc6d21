# Sourced by the fracture tests: the notched pure-shear sheet they pull (Gamma = 165 J/m^2
# from examples/notched_pure_shear_gamma.yaml, dx = 1 mm, 30 mm wide, 10 mm notch), and
# fail. Needs src (BAPD_SOURCE_DIR) and BAPD_EXE.
fail() { echo "FAILED: $*"; exit 1; }
sheet=(-options_file_yaml "$src/examples/notched_pure_shear_gamma.yaml" -body_dx 0.001 -body_width 0.03
       -body_notches 0.02,0.005,0.03,0.005 -probe_notch_mouth_top_at 0.03,0.0052 -probe_notch_mouth_bottom_at 0.03,0.0048
       -progress_interval 1000000)
# run_sheet DIR OPTIONS...: the sheet on 1 rank into DIR (its log DIR.log), or fail.
run_sheet() {
  local dir="$1"
  shift
  timeout 280 mpiexec -n 1 --oversubscribe --bind-to none "$BAPD_EXE" "${sheet[@]}" "$@" -output_dir "$dir" > "$dir.log" 2>&1 ||
    { tail -n 5 "$dir.log"; fail "the sheet did not run"; }
}
