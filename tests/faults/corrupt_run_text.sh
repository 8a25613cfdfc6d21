#!/usr/bin/env bash
# One byte changed in the text a checkpoint stores and a restart restores:
# /run/history (the rows history.csv is continued from) or /run/options (the scene):
# the restart is refused with one message, before any step; the unchanged file is
# accepted.
source "$BAPD_SOURCE_DIR/tests/faults/common.sh"
work="faults_corrupt_run_text"
rm -rf "$work" && mkdir -p "$work" || exit 1
bounded "$work/good.log" 2 "$TINY" -end_step 10 -checkpoint_interval 10 -output_interval 2 -output_dir "$work/good"
((STATUS == 0)) || fail "the checkpoint could not be written"
for dataset in history options; do
  cp "$work/good/checkpoint.h5" "$work/$dataset.h5"
  "$PYTHON" - "$work/$dataset.h5" "run/$dataset" << 'PY' || fail "could not change a byte of /run/$dataset"
import sys
import h5py
path, name = sys.argv[1], sys.argv[2]
with h5py.File(path, "r") as f:
    data = f[name][...].tobytes()
    # a digit in the middle of the text: still a valid-looking history or option value
    k = next(i for i in range(len(data) // 2, len(data)) if chr(data[i]).isdigit())
    offset = f[name].id.get_offset() + k
with open(path, "r+b") as f:
    f.seek(offset)
    byte = f.read(1)
    f.seek(offset)
    f.write(bytes([ord("7") if byte != b"7" else ord("3")]))
PY
  ranks=$([ $dataset = history ] && echo 1 || echo 2) # both rank counts, one run each
  bounded "$work/$dataset.log" "$ranks" -restart "$work/$dataset.h5" -output_dir "$work/out_$dataset"
  stopped_cleanly "$work/$dataset.h5" "is corrupt"
  grep -q "^step " "$log" && fail "steps were taken from a corrupt checkpoint"
  ok "one byte of /run/$dataset changed, $ranks rank(s)"
done
bounded "$work/continued.log" 2 -restart "$work/good/checkpoint.h5" -end_step 20 -output_dir "$work/continued"
((STATUS == 0)) || fail "the unchanged checkpoint is refused"
echo "ok   the unchanged checkpoint continues"
