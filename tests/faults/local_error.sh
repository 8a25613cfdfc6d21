#!/usr/bin/env bash
# An error that only some ranks see must not hang the run, and one that every rank
# sees alone (PETSC_COMM_SELF) must be printed once (src/solver/driver/errors.cpp, FinishRun).
#   local_error.sh PATH/TO/input_local_error
set -uo pipefail
exe="$1"
failures=0
run() { # MODE: runs the program on 2 ranks, prints the exit code
  timeout 60 mpiexec -q -n 2 --oversubscribe --bind-to none "$exe" -mode "$1" > "local_error_$1.log" 2>&1
  echo $?
}
check() { # MODE RC WHAT
  local mode="$1" rc="$2" problems=""
  ((rc == 124)) && problems+=" timed out: the ranks hung;"
  ((rc == 0)) && problems+=" exit code 0;"
  [ "$(grep -c "bapd: error: -mode $mode: a rank-local input error" "local_error_$mode.log")" = 1 ] || problems+=" want the message exactly once;"
  grep -q "PETSC ERROR" "local_error_$mode.log" && problems+=" a PETSc error stack;"
  if [ -n "$problems" ]; then
    echo "FAIL $mode (exit $rc):$problems"; sed 's/^/    | /' "local_error_$mode.log"; failures=$((failures + 1))
  else
    echo "ok   $mode (exit $rc): $(grep "bapd: error" "local_error_$mode.log")"
  fi
}
# Rank 1 fails while rank 0 waits in MPI_Barrier: the job is stopped (MPI_Abort).
check alone "$(run alone)"
# Both ranks fail with the same rank-local error: a clean exit 1, the message once.
rc=$(run all)
check all "$rc"
((rc == 1)) || { echo "FAIL all: exit code $rc, want 1 (a clean stop, no abort)"; failures=$((failures + 1)); }
grep -q "MPI_ABORT" local_error_all.log && { echo "FAIL all: aborted"; failures=$((failures + 1)); }
exit $((failures > 0))
