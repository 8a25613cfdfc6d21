#!/usr/bin/env bash
# A disk that fills during a run (issue 17): every rank stops within seconds with one
# `bapd: error:` line naming the file and the cause, exits non-zero, and loses
# nothing already written: history.csv keeps whole rows, the same as an undisturbed
# run's; the last good checkpoint still restarts; fields.xdmf lists only files that
# are there and read back.
#   full_disk.sh WHAT RANKS    WHAT: checkpoint, fields, history or static
# The disk is a small tmpfs (tests/faults/common.sh); its size lets the first
# checkpoint or field files be written and the next one not.
source "$BAPD_SOURCE_DIR/tests/faults/common.sh"
what="$1" ranks="$2"
work="faults_full_disk_${what}_np$ranks"
rm -rf "$work" && mkdir -p "$work" || exit 1
disk="$PWD/$work/disk"
out="$disk/out"

case "$what" in
  checkpoint) # checkpoint 114 KB (150 KB reserved): the one of step 10 fits, the next not
    kb=250 scene=("$TINY" -checkpoint_interval 10 -output_interval 2) file=checkpoint.h5 ;;
  fields) # field files of 164 KB (196 KB reserved): steps 0 and 2 fit, step 4 not
    kb=400 scene=("$TINY" -output_fields -output_fields_interval 2 -output_interval 2) file=fields/step_ ;;
  history) # 4 KB free: about 20 rows of history.csv
    kb=64 scene=("$TINY" -output_interval 1) file=history.csv ;;
  static) # 4 KB free: history.csv up to the step (140) where the first hold ends is 4071
          # bytes, one tmpfs page; static_states.csv's first row needs another
    kb=64
    scene=(-body_width 0.03 -body_height 0.012 -body_thickness 0.003 -body_dx 0.001 -body_notches 0.02,0.006,0.03,0.006
           -horizon_factor 3.015 -material_mu 4.55e3 -material_Jm 162.6 -material_bulk_ratio 100 -material_density 1000
           -load_sets top,bottom -load_top_region top -load_top_x fixed -load_top_y stretch -load_bottom_region bottom
           -load_bottom_x fixed -load_bottom_y fixed -probes mouth -probe_mouth_at 0.03,0.0062 -damping 40
           -load_schedule 0,1,0.05,1.2,1.0,1.2 -static_tolerance 1e-3 -output_interval 10 -ts_max_steps 160)
    file=static_states.csv ;;
  *) echo "usage: full_disk.sh checkpoint|fields|history|static RANKS"; exit 2 ;;
esac

# The undisturbed run, on the ordinary disk.
bounded "$work/reference.log" "$ranks" "${scene[@]}" -output_dir "$work/reference" -progress_interval 100000
((STATUS == 0)) || fail "the undisturbed run failed"

small_disk "$disk" "$kb"
case "$what" in
  history) [ "$DISK" = tmpfs ] && head -c $((60 * 1024)) /dev/zero > "$disk/filler" ;;
  static)
    [ "$DISK" = tmpfs ] || { echo "SKIP: static_states.csv is the smaller file: it needs a disk the files share (tmpfs)"; exit 77; }
    head -c $((60 * 1024)) /dev/zero > "$disk/filler" ;;
esac
start=$(date +%s.%N)
bounded "$work/run.log" "$ranks" "${scene[@]}" -output_dir "$out" -progress_interval 100000
fault_status=$STATUS
seconds=$(echo "$(date +%s.%N) - $start" | bc)
stopped_cleanly "$file" "$CAUSE"
# history.csv: whole rows, those of the undisturbed run.
whole_rows "$out/history.csv"
same_prefix "$out/history.csv" "$work/reference/history.csv"
rows="$(($(wc -l < "$out/history.csv") - 1)) history row(s) kept"

case "$what" in
  checkpoint)
    [ ! -e "$out/checkpoint.h5.tmp" ] || fail "a partial checkpoint.h5.tmp was left on the full disk"
    if [ -f "$out/checkpoint.h5" ]; then
      # The last good checkpoint continues the run, to the same history.
      bounded "$work/continued.log" "$ranks" -restart "$out/checkpoint.h5" -output_dir "$work/continued" -progress_interval 100000
      ((STATUS == 0)) || fail "the checkpoint left on the full disk does not restart"
      cmp -s "$work/continued/history.csv" "$work/reference/history.csv" || fail "the continued run's history differs from the undisturbed run's"
      rows="$rows; checkpoint.h5 restarts to the undisturbed history"
    elif [ "$DISK" = tmpfs ]; then
      fail "the checkpoint of step 10 (which fits) is missing"
    fi ;;
  fields)
    if [ -f "$out/fields.xdmf" ]; then
      "$PYTHON" - "$out" << 'PY' || fail "fields.xdmf lists a file that is missing or unreadable"
import re, sys
import h5py
out = sys.argv[1]
files = sorted(set(re.findall(r'>(fields/step_\d+\.h5):', open(f"{out}/fields.xdmf").read())))
assert files, "no frame listed"
for name in files:
    with h5py.File(f"{out}/{name}", "r") as f:
        f["displacement"][...]
print(f"fields.xdmf lists {len(files)} readable file(s)")
PY
    elif [ "$DISK" = tmpfs ]; then
      fail "fields.xdmf of the frames that fit is missing"
    fi ;;
  static)
    [ "$(grep -c '^Static at' "$work/reference.log")" -ge 1 ] || fail "the undisturbed run ended no hold (the case tests nothing)" ;;
esac
[ "$what" = checkpoint ] || [ ! -e "$out/checkpoint.h5.tmp" ] || fail "a temporary file was left"
log="$work/run.log" STATUS=$fault_status ok "disk full ($DISK) during $what on $ranks rank(s), stopped in ${seconds%???????} s, $rows"
