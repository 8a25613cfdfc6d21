#!/usr/bin/env bash
# Checkpoints that cannot be continued are refused before any step, with one line
# "bapd: error: ..." and a non-zero exit: a truncated file, a file that is not HDF5,
# an unknown format version, damaged data (checksum), a missing file, and a
# checkpoint of another body. No HDF5 error stack, no PETSc traceback, no crash.
set -euo pipefail
source "$BAPD_SOURCE_DIR/tests/mpi/restart/common.sh"
work="restart_refused"
rm -rf "$work"; mkdir -p "$work"
scene=("${NOTCHED[@]}" "${FRACTURE[@]}" -body_dx 0.001)
run 2 "$work/good" "${scene[@]}" -end_step 10 -checkpoint_interval 10
good="$work/good/checkpoint.h5"

size=$(stat -c %s "$good")
head -c $((size / 2)) "$good" > "$work/truncated.h5"
echo "not a checkpoint" > "$work/text.h5"
cp "$good" "$work/version.h5"
cp "$good" "$work/damaged.h5"
$PYTHON - "$work" << 'PY'
import sys
import h5py
work = sys.argv[1]
with h5py.File(f"{work}/version.h5", "r+") as f:
    f.attrs.modify("format_version", 99)
with h5py.File(f"{work}/damaged.h5", "r") as f:
    offset = f["bonds/c33"].id.get_offset() + 8 * 100  # one C33 value
with open(f"{work}/damaged.h5", "r+b") as f:
    f.seek(offset)
    byte = f.read(1)
    f.seek(offset)
    f.write(bytes([byte[0] ^ 0xFF]))
PY

# refused NAME EXPECTED OPTIONS...: bapd must stop with one error line matching EXPECTED.
refused() {
  local name="$1" expected="$2"
  shift 2
  local log="$work/$name.log" status=0
  mpiexec -n 2 --oversubscribe --bind-to none "$BAPD_EXE" "$@" -output_dir "$work/out_$name" > "$log" 2>&1 || status=$?
  echo "--- $name (exit status $status)"
  grep "bapd: error:" "$log" || true
  [ "$status" -ne 0 ] || { cat "$log"; fail "$name: accepted"; }
  [ "$status" -lt 128 ] || { cat "$log"; fail "$name: died on a signal"; }
  [ "$(grep -c 'bapd: error:' "$log")" = 1 ] || { cat "$log"; fail "$name: expected exactly one error line"; }
  grep -q "bapd: error: .*$expected" "$log" || { cat "$log"; fail "$name: the message does not say '$expected'"; }
  if grep -q -e "HDF5-DIAG" -e "PETSC ERROR" "$log"; then cat "$log"; fail "$name: error stack printed"; fi
  grep -q "^step " "$log" && fail "$name: steps were taken" || true
}
refused truncated "not an HDF5 file, or it is truncated" -restart "$work/truncated.h5"
refused text "not an HDF5 file, or it is truncated" -restart "$work/text.h5"
refused version "format version 99" -restart "$work/version.h5"
refused damaged "is corrupt" -restart "$work/damaged.h5"
refused missing "no such file" -restart "$work/missing.h5"
refused other_body "belongs to another body" "${scene[@]}" -body_dx 0.0005 -restart "$good"
refused other_notch "belongs to another body" "${scene[@]}" -body_notches 0.015,0.006,0.03,0.006 -restart "$good"
# The good one is accepted.
run 2 "$work/continued" -restart "$good" -end_step 20
echo "bad checkpoints refused, the good one continues"
