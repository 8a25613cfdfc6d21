#!/usr/bin/env bash
# Horizon at the extreme: below delta = sqrt(2) dx every bond-associated family
# of the square lattice is collinear, so every shape tensor is singular and no bond
# carries force. The run must stop before any step with one message that names
# -horizon_factor (not later, in the stable-step estimate, with a message claiming
# that every degree of freedom was held). At 1.5 dx the same scene, notched, runs.
set -uo pipefail
# Every run is on 1 rank: mpiexec returns at once after an error exit instead of waiting
# 2 s for ranks that are not there (tests/faults/bad_input.sh explains).
export OMPI_MCA_odls_base_sigkill_timeout=0
work="stability_small_horizon"
rm -rf "$work" && mkdir -p "$work" || exit 1
scene=(-options_file_yaml "$BAPD_SOURCE_DIR/tests/data/scenes/tiny.yaml" -progress_interval 1000000)
status=0
for factor in 1 1.2; do
  mpiexec -n 1 --oversubscribe --bind-to none "$BAPD_EXE" "${scene[@]}" -horizon_factor $factor -output_dir "$work/h$factor" \
    > "$work/h$factor.log" 2>&1
  rc=$?
  line=$(grep "error:" "$work/h$factor.log")
  if ((rc == 0)) || [ "$(grep -c "error:" "$work/h$factor.log")" != 1 ] || ! grep -qF -- "-horizon_factor $factor: every bond" <<< "$line" ||
     ! grep -q "Bonds with a singular shape tensor (carry no force): " "$work/h$factor.log"; then
    echo "FAIL horizon factor $factor (exit $rc):"; sed 's/^/    | /' "$work/h$factor.log"; status=1
  else
    echo "ok   horizon factor $factor: $(grep "Bonds with a singular" "$work/h$factor.log"); $line"
  fi
done
mpiexec -n 1 --oversubscribe --bind-to none "$BAPD_EXE" "${scene[@]}" -horizon_factor 1.5 -body_notches 0,0.005,0.004,0.005 \
  -output_dir "$work/h1.5" > "$work/h1.5.log" 2>&1 || { echo "FAIL horizon factor 1.5 (notched) did not run:"; cat "$work/h1.5.log"; status=1; }
((status == 0)) && echo "ok   horizon factor 1.5 (notched): ran, $(grep -c "Bonds with a singular" "$work/h1.5.log") singular-tensor line(s)"
exit $status
