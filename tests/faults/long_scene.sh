# A run that lasts (sourced): the notched sheet of tests/mpi/restart/common.sh at dx = 1 mm
# (360 points), damped, pulled slowly: ~10^5 steps, far more than any case waits for.
LONG=(-body_width 0.03 -body_height 0.012 -body_thickness 0.003 -body_dx 0.001 -body_notches 0.02,0.006,0.03,0.006
      -horizon_factor 3.015 -material_mu 4.55e3 -material_Jm 162.6 -material_bulk_ratio 100 -material_density 1000
      -load_sets top,bottom -load_top_region top -load_top_x fixed -load_top_y stretch -load_bottom_region bottom
      -load_bottom_x fixed -load_bottom_y fixed -probes mouth -probe_mouth_at 0.03,0.0062 -damping 40
      -load_schedule 0,1,40,1.2 -output_interval 10 -progress_interval 100)

# start_long LOG RANKS ARGS...: the long run in the background (PID), bounded by 60 s;
# returns once it has taken 100 steps.
start_long() {
  log="$1"
  local ranks="$2"
  shift 2
  timeout 60 "$BAPD_SOURCE_DIR/run_mpi.sh" -n "$ranks" "${LONG[@]}" "$@" > "$log" 2>&1 &
  PID=$!
  local _
  for _ in $(seq 600); do grep -q '^step ' "$log" 2> /dev/null && return 0; sleep 0.1; done
  fail "the run did not start stepping"
}

# finish_long: waits for the run; sets STATUS and SECONDS_LEFT (from the call to the end).
finish_long() {
  local start
  start=$(date +%s.%N)
  wait "$PID"
  STATUS=$?
  SECONDS_LEFT=$(echo "$(date +%s.%N) - $start" | bc)
  SECONDS_LEFT=${SECONDS_LEFT%???????}
}
