#!/usr/bin/env bash
# The undisturbed runs the full-disk cases compare their history.csv with (ctest
# fixture of the faults tests), one per scene of full_disk_scenes.sh, on 2 ranks
# (the results do not depend on the rank count: tests/mpi).
source "$BAPD_SOURCE_DIR/tests/faults/common.sh"
rm -rf faults_reference && mkdir -p faults_reference || exit 1
for what in checkpoint fields history static final_state; do
  source "$BAPD_SOURCE_DIR/tests/faults/full_disk_scenes.sh"
  bounded "faults_reference/$what.log" 2 "${scene[@]}" -output_dir "faults_reference/$what" -progress_interval 100000
  ((STATUS == 0)) || fail "the undisturbed $what run failed"
done
echo "ok   undisturbed runs in faults_reference"
