#!/usr/bin/env bash
# What mpiexec needs before bapd starts, missing: run_mpi.sh says so in one line
# naming the setting and the fix, exits non-zero, and starts nothing (mpiexec's own
# failure is a page of PMIx errors, or a hang):
#   TMPDIR a directory that does not exist; TMPDIR on a full disk; ulimit -n 16.
#   launch_limits.sh
source "$BAPD_SOURCE_DIR/tests/faults/common.sh"
work="faults_launch_limits"
rm -rf "$work" && mkdir -p "$work" || exit 1

# limited NAME KEY COMMAND...: the tiny scene through run_mpi.sh under COMMAND's settings.
limited() {
  local name="$1" key="$2"
  shift 2
  log="$work/$name.log"
  timeout -k 5 60 "$@" "$BAPD_SOURCE_DIR/run_mpi.sh" -n 2 "$TINY" -end_step 5 -output_dir "$work/$name" > "$log" 2>&1
  STATUS=$?
  stopped_cleanly "$key"
  grep -q -e "PMIX ERROR" -e "ORTE_ERROR_LOG" -e "MPI_Init" "$log" && fail "Open MPI's own errors were printed"
  [ ! -e "$work/$name/history.csv" ] || fail "the run started although it was refused"
  ok "$name"
}

limited tmpdir_missing "TMPDIR '$PWD/$work/no_such_dir' is not a writable directory" env TMPDIR="$PWD/$work/no_such_dir"
small_disk "$PWD/$work/tmp" 16
head -c $((16 * 1024)) /dev/zero > "$work/tmp/filler" 2> /dev/null
limited tmpdir_full "TMPDIR '$PWD/$work/tmp' has 0 kB free" env TMPDIR="$PWD/$work/tmp"
limited open_files "ulimit -n 16" bash -c 'ulimit -n 16 && exec "$@"' limit
