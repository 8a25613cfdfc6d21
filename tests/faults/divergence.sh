#!/usr/bin/env bash
# Divergence: a time step above the stable one must stop every rank together
# within a bounded number of steps, with one message that names -time_step and gives
# the step, the time and a point, a non-zero exit code, and history.csv rows up to the
# blow-up. The same scene below the stable step, fracturing, must run to its end (no
# false alarm).
#   divergence.sh RANKS        (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
set -uo pipefail
ranks="$1"
# Each diverging run exits non-zero, after which mpiexec waits 2.1 s on 1 rank
# (bad_input.sh explains): six of those cases.
((ranks == 1)) && export OMPI_MCA_odls_base_sigkill_timeout=0
source_dir="$BAPD_SOURCE_DIR"
run_mpi="$source_dir/run_mpi.sh"
scene="$source_dir/tests/data/scenes/tiny.yaml"
work="input_divergence_np$ranks"
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
failures=0

fail() {
  echo "FAIL $1"
  [ -f "$2" ] && sed 's/^/    | /' "$2"
  failures=$((failures + 1))
}

# expect_divergence NAME MAX_STEP TEXT ARGS...: the run stops by step MAX_STEP.
expect_divergence() {
  local name="$1" max_step="$2" text="$3" rc
  shift 3
  timeout 60 "$run_mpi" -n "$ranks" "$scene" -output_dir "$name" -output_interval 1 "$@" > "$name.log" 2>&1
  rc=$?
  if ((rc == 0 || rc == 124 || rc >= 128)); then fail "$name: exit code $rc (want a clean non-zero exit)" "$name.log"; return; fi
  local line
  line=$(grep "error:" "$name.log")
  if [ "$(grep -c "error:" "$name.log")" != 1 ]; then fail "$name: want exactly one error line" "$name.log"; return; fi
  grep -qE "PETSC ERROR|Segmentation|core dumped|Caught signal|MPI_ABORT" "$name.log" && { fail "$name: crash, abort or PETSc stack" "$name.log"; return; }
  for want in "$text" "-time_step" "(t = " "step "; do
    grep -qF -- "$want" <<< "$line" || { fail "$name: no '$want' in: $line" "$name.log"; return; }
  done
  local step
  step=$(sed -nE 's/.* at step ([0-9]+).*/\1/p' <<< "$line")
  if [ -z "$step" ] || ((step > max_step)); then fail "$name: stopped at step '${step}', want <= $max_step" "$name.log"; return; fi
  # history.csv: a row for every step before the blow-up (written and flushed as the run went).
  local rows
  rows=$(awk -F, 'NR > 1 && $1 == NR - 2 { n++ } END { print n + 0 }' "$name/history.csv" 2>/dev/null)
  if [ -z "$rows" ] || ((rows < step)); then fail "$name: history.csv holds $rows consecutive rows, want the $step before step $step" "$name.log"; return; fi
  echo "ok   $name (stopped at step $step, $rows history rows): $line"
}

# Without failure the unstable mode inverts bonds within a few steps.
expect_divergence unstable_elastic 20 "inverted" -time_step_safety 1.5
# With failure, inverted and overstretched bonds break instead and the body would
# shatter with exit code 0: the runaway kinetic energy stops the run. With the
# energy-consistent form (the default) the kinetic energy jumps from 1e-5 J to 918 J
# in one step and stays: the total of the step before shows the energy was created.
expect_divergence unstable_fracture 20 "the run diverged at step" -time_step_safety 1.5 -failure_critical_stretch 1.5
expect_divergence unstable_fracture_bond_only 20 "the run diverged at step" -time_step_safety 1.5 -failure_critical_stretch 1.5 -force_form bond_only
expect_divergence unstable_fracture_slow 40 "the run diverged at step" -time_step_safety 1.1 -failure_critical_stretch 7.2
# An explicit -time_step above the stable one (2.6e-4 s here), which only
# -time_step_allow_unstable lets run (without it the step is refused: silent_results.sh).
expect_divergence unstable_time_step 20 "the run diverged at step" -time_step 4e-4 -time_step_allow_unstable -failure_critical_stretch 1.5
# A 3D body: the same clean stop, and the fastest point's position with its z.
scene="$source_dir/tests/data/scenes/block_3d.yaml"
expect_divergence unstable_fracture_3d 20 "the run diverged at step" -time_step_safety 1.5 -failure_critical_stretch 1.5
if ! grep -qE 'Fastest point: [0-9]+, reference position \([^,()]+, [^,()]+, [^,()]+\) m' unstable_fracture_3d.log; then
  fail "unstable_fracture_3d: the fastest point's position is not given with three coordinates" unstable_fracture_3d.log
fi
scene="$source_dir/tests/data/scenes/tiny.yaml"

# No false alarm: below the stable step, a notch that opens and bonds that break (the
# kinetic energy jumps as they go), undamped, and a fast ramp from rest after a hold.
legit=(-body_notches 0,0.005,0.004,0.005 -failure_critical_stretch 1.02 -load_schedule 0,1,0.002,1,0.006,1.1 -end_time 0.02)
timeout 60 "$run_mpi" -n "$ranks" "$scene" -output_dir legit "${legit[@]}" > legit.log 2>&1
rc=$?
broken=$(sed -nE 's/^broken bonds: ([0-9]+)/\1/p' legit.log)
if ((rc != 0)); then fail "legit: a fracturing run below the stable step stopped (exit $rc)" legit.log
elif [ -z "$broken" ] || ((broken == 0)); then fail "legit: no bond broke, the scene does not test what it should" legit.log
else echo "ok   legit: ran to the end, $broken bonds broken"
fi

if ((failures)); then
  echo "$failures case(s) failed"
  exit 1
fi
echo "every divergence was caught cleanly on $ranks rank(s)"
