#!/usr/bin/env bash
# A disk that fills at some point of a parallel field file's write, not only where
# full_disk.sh's sizes put it: the tiny sheet writes a field file every step on RANKS
# ranks, without the space reservation (as on a disk another program fills), onto disks
# of 6 sizes, so that the disk fills at the creation, inside a dataset, between two,
# or at HDF5's collective close (its metadata). Each run must stop cleanly (or fit):
# one `bapd: error:` line naming the file and the cause, no crash (a failed write used
# to leave the ranks in mismatched collectives inside H5Fclose: a segfault or a hang),
# and fields.xdmf listing only files that read back.
#   full_disk_sizes.sh RANKS
source "$BAPD_SOURCE_DIR/tests/faults/common.sh"
ranks="$1"
work="faults_full_disk_sizes_np$ranks"
rm -rf "$work" && mkdir -p "$work" || exit 1
export BAPD_TEST_NO_SPACE_RESERVATION=1
for kb in 346 394 442 490 514 562; do
  disk="$PWD/$work/disk_$kb"
  small_disk "$disk" "$kb"
  # (45 s, then SIGKILL: a hung collective close ignores the stop that run_mpi.sh passes on)
  log="$work/run_$kb.log"
  timeout -k 5 45 "$BAPD_SOURCE_DIR/run_mpi.sh" -n "$ranks" "$TINY" -load_grip_placement inside -output_fields \
    -output_fields_interval 1 -output_interval 2 -end_step 12 -output_dir "$disk/out" -progress_interval 100000 > "$log" 2>&1
  STATUS=$?
  ((STATUS != 124 && STATUS != 137)) || fail "the run hung on the $kb KB disk (killed after 45 s)"
  if ((STATUS != 0)); then
    stopped_cleanly "$CAUSE"
    whole_rows "$disk/out/history.csv"
  fi
  if [ -f "$disk/out/fields.xdmf" ]; then
    "$PYTHON" - "$disk/out" << 'PY' || fail "fields.xdmf lists a file that is missing or unreadable ($kb KB)"
import re, sys
import h5py
out = sys.argv[1]
for name in sorted(set(re.findall(r'>(fields/step_\d+\.h5):', open(f"{out}/fields.xdmf").read()))):
    with h5py.File(f"{out}/{name}", "r") as f:
        f["displacement"][...]
PY
  fi
  ls "$disk/out/fields" 2> /dev/null | grep -q '\.room$' && fail "a metadata room file was left in $disk/out/fields"
  echo "ok   $kb KB: exit $STATUS, $(grep 'bapd: error:' "$log" | cut -c1-110)"
  umount "$disk"
done
echo "ok   a parallel field write on $ranks rank(s) stops cleanly wherever the disk fills"
