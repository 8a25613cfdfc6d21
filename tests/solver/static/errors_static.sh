#!/usr/bin/env bash
# What the static solver refuses, and a load step that cannot converge: each ends with one
# "bapd: error:" naming the option or the stretch and what to change, and a non-zero exit.
#   errors_static.sh       (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
. "$(dirname "$0")/common.sh" static_errors
# Every run is on 1 rank: mpiexec returns at once after an error exit instead of waiting
# 2 s for ranks that are not there (tests/faults/bad_input.sh explains).
export OMPI_MCA_odls_base_sigkill_timeout=0
scene=(-options_file_yaml "$src/tests/data/scenes/tiny.yaml" -progress_wall_interval 0 -solver static)
# expect NAME PATTERN OPTIONS...: exit non-zero with a "bapd: error:" line matching PATTERN.
expect() {
  local name="$1" pattern="$2"
  shift 2
  timeout 300 mpiexec -n 1 "$BAPD_EXE" "${scene[@]}" -output_dir "$name" "$@" > "$name.log" 2>&1
  local code=$?
  ((code != 0)) || fail "$name: exit 0"
  grep -E "bapd: error:.*$pattern" "$name.log" > /dev/null || { fail "$name: no error matching '$pattern'"; tail -5 "$name.log"; }
}
expect softening "-solver static breaks bonds at once .* but does not soften them yet: remove -failure_softening" \
  -failure_fracture_energy 165 -failure_softening linear
expect onset "-static_onset_tolerance" -static_onset_tolerance 0
expect checkpoint "-solver static writes no checkpoints.*-checkpoint_interval" -checkpoint_interval 10
expect bond_only "-solver static needs -force_form energy_consistent" -force_form bond_only
expect solver "-solver 'newton' is not a solver" -solver newton
expect step "-static_stretch_step" -static_stretch_step 0
# A load step that cannot converge (here one Newton iteration allowed, -snes_max_it 1, so
# that no step reaches 1e-10 of the reactions): cutbacks down to -static_stretch_step_min,
# then one error naming the last stretch reached and the options to change, not a hang.
expect no_convergence "no static state found beyond stretch 1.00000 on the way to 1.50000.*-static_stretch_step_min.*-snes_max_it" \
  -load_schedule 0,1,1,1.5 -snes_max_it 1 -static_stretch_step_min 0.05
finish errors_static
