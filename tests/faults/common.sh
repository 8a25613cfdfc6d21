# Shared by the fault-injection tests (sourced): a small disk, a bounded run, and the
# checks every case makes (exit code, one message, no hang, nothing lost).
set -uo pipefail
SCRIPT_ARGS=("$@") # (the caller's arguments: small_disk may run the test again)
PYTHON=/usr/bin/python3
TINY="$BAPD_SOURCE_DIR/tests/data/scenes/tiny.yaml" # 400 points, 49 steps

fail() {
  echo "FAIL: $*"
  [ -f "${log:-}" ] && sed 's/^/    | /' "$log"
  exit 1
}

# small_disk DIR KB: a file system of KB kilobytes mounted at DIR: a tmpfs, as root
# (as in CI). Without root the whole test runs again in a user namespace
# (`unshare --user --map-root-user --mount`), where the mount needs no privilege
# (BAPD_FAULTS_DISK=userns forces that route). `ulimit -f` is no substitute: Open
# MPI's PMIx writes its shared-memory segments under the same limit and mpiexec dies
# of SIGXFSZ. A test skips (exit 77) only if neither works.
small_disk() {
  local dir="$1" kb="$2"
  mountpoint -q "$dir" 2> /dev/null && umount "$dir"
  rm -rf "$dir" && mkdir -p "$dir" || exit 1
  if { [ "${BAPD_FAULTS_DISK:-}" != userns ] || [ -n "${BAPD_FAULTS_IN_USERNS:-}" ]; } &&
    mount -t tmpfs -o "size=${kb}k" tmpfs "$dir" 2> /dev/null; then
    DISK=tmpfs
    trap "umount '$dir' 2> /dev/null" EXIT
    if [ -n "${BAPD_FAULTS_IN_USERNS:-}" ]; then
      DISK="tmpfs in a user namespace"
      # (Open MPI's session directory of "root" in /tmp would be the real root's)
      export TMPDIR="$dir.tmp"
      mkdir -p "$TMPDIR"
    fi
  elif [ -z "${BAPD_FAULTS_IN_USERNS:-}" ] && unshare --user --map-root-user --mount true 2> /dev/null; then
    exec unshare --user --map-root-user --mount env BAPD_FAULTS_IN_USERNS=1 bash "$0" "${SCRIPT_ARGS[@]}"
  else
    echo "SKIP: no small file system: tmpfs cannot be mounted here (not root, no user namespaces)"
    exit 77
  fi
  CAUSE="No space left on device"
}

# bounded LOG RANKS ARGS...: run_mpi.sh on RANKS ranks, killed after 60 s (a hang);
# sets STATUS.
bounded() {
  log="$1"
  local ranks="$2"
  shift 2
  timeout 60 "$BAPD_SOURCE_DIR/run_mpi.sh" -n "$ranks" "$@" > "$log" 2>&1
  STATUS=$?
}

# stopped_cleanly KEY...: the run failed without hanging or crashing, printed exactly
# one `bapd: error:` line and it holds every KEY (the file, the cause); no stack.
stopped_cleanly() {
  ((STATUS != 124)) || fail "the run hung (killed after 60 s)"
  ((STATUS != 0)) || fail "exit status 0 although the output could not be written"
  ((STATUS < 128)) || fail "bapd crashed (exit status $STATUS)"
  [ "$(grep -c 'bapd: error:' "$log")" = 1 ] || fail "expected exactly one 'bapd: error:' line"
  local key
  for key in "$@"; do grep 'bapd: error:' "$log" | grep -q -F -- "$key" || fail "the error line does not say '$key'"; done
  if grep -q -e "HDF5-DIAG" -e "PETSC ERROR" -e "Segmentation" -e "signal 11" "$log"; then fail "an error stack or a crash was printed"; fi
  return 0
}

# stopped_saying REGEX: the error line matches REGEX (grep -E) too.
stopped_saying() { grep 'bapd: error:' "$log" | grep -q -E -- "$1" || fail "the error line does not match '$1'"; }

# whole_rows FILE: every line of a CSV file complete (as many fields as the header,
# a final newline) and the steps (history.csv's first column) increasing.
whole_rows() {
  "$PYTHON" - "$1" << 'PY' || fail "$1 has a cut or broken row"
import sys
text = open(sys.argv[1]).read()
assert text.endswith("\n"), "no final newline"
rows = [r.split(",") for r in text.splitlines()]
assert len(rows) >= 2, "no data row"
n = len(rows[0])
assert all(len(r) == n for r in rows), "a row with another number of fields"
if rows[0][0] == "step":
    steps = [int(r[0]) for r in rows[1:]]
    assert steps == sorted(set(steps)), "steps not increasing"
PY
}

# same_prefix FILE REFERENCE: FILE is the first lines of REFERENCE, byte for byte.
same_prefix() {
  head -n "$(wc -l < "$1")" "$2" | cmp -s - "$1" || fail "$1 differs from the same rows of an undisturbed run ($2)"
}

# ok MESSAGE: the case passed; print its error line for the record.
ok() { echo "ok   $*: exit $STATUS, $(grep 'bapd: error:' "$log" | cut -c1-160)"; }
