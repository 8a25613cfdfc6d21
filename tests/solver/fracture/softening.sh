#!/usr/bin/env bash
# Softening bonds (-failure_softening linear, and time with tau = 2 ms; docs/method.md
# 5.4) on a small notched pure-shear sheet (dx = 1 mm, 30 mm wide, 10 mm notch, Gamma =
# 60 J/m^2) pulled until bonds have softened and 20 or more have broken: the same history, final state and
# broken bonds on 1 and 2 ranks and after a restart on 2 ranks from a 1-rank checkpoint
# taken while bonds soften (tolerance 0: the damage is in the checkpoint), and the
# energy balance closed (the softening's dissipation is counted).
#   softening.sh   (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
set -uo pipefail
src="$BAPD_SOURCE_DIR"
work="fracture_softening"
rm -rf "$work" && mkdir -p "$work" || exit 1
source "$src/tests/solver/fracture/common.sh"
run() { # run RANKS DIR OPTIONS...
  local ranks="$1" dir="$2"
  shift 2
  timeout 200 mpiexec -n "$ranks" --oversubscribe --bind-to none "$BAPD_EXE" "$@" -output_dir "$dir" > "$dir.log" 2>&1 ||
    { tail -n 5 "$dir.log"; fail "the run in $dir failed"; }
}
scene=("${sheet[@]}" -load_schedule 0,1,0.2,3.3 -end_time 0.2 -failure_fracture_energy 60 -output_interval 10 -output_final_state)
N=330 M=450 # linear: bonds soften from step ~210, 16 have broken by step 389; time: 106 broken by step 450 (measured)
check() { # check NAME LAW_OPTIONS...
  local name="$1" dir="$work/$1"
  shift
  mkdir -p "$dir" || exit 1
  run 1 "$dir/np1" "${scene[@]}" "$@" -end_step $M
  run 2 "$dir/np2" "${scene[@]}" "$@" -end_step $M
  run 1 "$dir/first" "${scene[@]}" "$@" -end_step $N -checkpoint_interval $N
  [ -f "$dir/first/checkpoint.h5" ] || fail "$name: no checkpoint after $N steps"
  run 2 "$dir/second" -restart "$dir/first/checkpoint.h5" -end_step $M
  read -r broken soft work_J residual_J < <(awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
    $1 == n { s = $c["fracture_dissipation_J"] }
    { b = $c["broken_bonds"]; w = $c["top_work_J"] + $c["bottom_work_J"]; r = $c["energy_balance_residual_J"] }
    END { print b, s, w, r }' n=$N "$dir/np1/history.csv")
  echo "$name, step $M: $broken broken bonds; dissipated by softening at step $N: $soft J; grips' work $work_J J, residual $residual_J J"
  awk -v s="$soft" 'BEGIN { exit !(s > 0) }' || fail "$name: no bond had softened by the checkpoint: the restart tests nothing"
  [ "$broken" -ge 20 ] || fail "$name: only $broken bonds broke: the case tests nothing"
  awk -v w="$work_J" -v r="$residual_J" 'BEGIN { exit !(r < 0 ? -r < 1e-3 * w : r < 1e-3 * w) }' ||
    fail "$name: the energy balance is off by $residual_J J of $work_J J (more than 0.1 %)"
  /usr/bin/python3 "$src/tests/mpi/compare_runs.py" --tolerance 0 "$dir/np1" "$dir/np2" "$dir/second" ||
    fail "$name: 2 ranks or the restart differ from the 1-rank run"
}
check linear -failure_softening linear
check time -failure_softening time -failure_softening_time 0.002
work="$work/linear"
# d is the state: a restart without the softening is refused with one message.
timeout 60 mpiexec -n 1 --oversubscribe --bind-to none "$BAPD_EXE" -restart "$work/first/checkpoint.h5" -failure_softening none \
  -end_step $M -output_dir "$work/refused" > "$work/refused.log" 2>&1 && fail "a restart without the softening was accepted"
grep -q "error: .*-failure_softening" "$work/refused.log" || fail "the refusal does not name -failure_softening: $(grep error "$work/refused.log")"
echo "fracture softening: ok"
