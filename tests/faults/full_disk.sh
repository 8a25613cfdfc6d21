#!/usr/bin/env bash
# A disk that fills during a run: every rank stops within seconds with one
# `bapd: error:` line naming the file and the cause, exits non-zero, and loses
# nothing already written: history.csv keeps whole rows, the same as an undisturbed
# run's; the last good checkpoint still restarts; fields.xdmf lists only files that
# are there and read back.
#   full_disk.sh WHAT RANKS    WHAT: checkpoint, fields, history, static, or
#                              checkpoint_late, fields_late (the writes themselves fail)
# The disk is a small tmpfs (tests/faults/common.sh); its size lets the first
# checkpoint or field files be written and the next one not (full_disk_scenes.sh).
source "$BAPD_SOURCE_DIR/tests/faults/common.sh"
what="$1" ranks="$2"
((ranks == 1)) && export OMPI_MCA_odls_base_sigkill_timeout=0 # (bad_input.sh explains)
work="faults_full_disk_${what}_np$ranks"
rm -rf "$work" && mkdir -p "$work" || exit 1
disk="$PWD/$work/disk"
out="$disk/out"

source "$BAPD_SOURCE_DIR/tests/faults/full_disk_scenes.sh"

# The undisturbed run, on the ordinary disk (faults.reference; rank-independent).
reference="$PWD/faults_reference/${what%_late}"
[ -f "$reference/history.csv" ] || fail "no undisturbed run in $reference (ctest runs faults.reference first)"

small_disk "$disk" "$kb"
case "$what" in
  history) head -c $((60 * 1024)) /dev/zero > "$disk/filler" ;; # 4 KB left
  final_state) head -c $((56 * 1024)) /dev/zero > "$disk/filler" ;; # 8 KB left
  static)
    # Room for history.csv up to the step where the first hold ends (the undisturbed
    # run's, in whole 4 KB tmpfs pages) and not a page more: static_states.csv's
    # first row finds none.
    hold_step=$(sed -n '2p' "$reference/static_states.csv" | cut -d, -f3)
    history_bytes=$(awk -F, -v s="$hold_step" 'NR == 1 || $1 <= s' "$reference/history.csv" | wc -c)
    pages=$(((history_bytes + 4095) / 4096))
    head -c $(((64 - 4 * pages) * 1024)) /dev/zero > "$disk/filler" ;;
esac
start=$(date +%s.%N)
bounded "$work/run.log" "$ranks" "${scene[@]}" -output_dir "$out" -progress_interval 100000
fault_status=$STATUS
seconds=$(echo "$(date +%s.%N) - $start" | bc)
stopped_cleanly "$file" "$CAUSE"
# history.csv: whole rows, those of the undisturbed run.
whole_rows "$out/history.csv"
same_prefix "$out/history.csv" "$reference/history.csv"
rows="$(($(wc -l < "$out/history.csv") - 1)) history row(s) kept"

case "$what" in
  checkpoint | checkpoint_late)
    [ ! -e "$out/checkpoint.h5.tmp" ] || fail "a partial checkpoint.h5.tmp was left on the full disk"
    if [ -f "$out/checkpoint.h5" ]; then
      # The last good checkpoint continues the run, to the same history.
      bounded "$work/continued.log" "$ranks" -restart "$out/checkpoint.h5" -output_dir "$work/continued" -progress_interval 100000
      ((STATUS == 0)) || fail "the checkpoint left on the full disk does not restart"
      cmp -s "$work/continued/history.csv" "$reference/history.csv" || fail "the continued run's history differs from the undisturbed run's"
      rows="$rows; checkpoint.h5 restarts to the undisturbed history"
    else
      fail "the checkpoint of step 10 (which fits) is missing"
    fi ;;
  fields | fields_late)
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
    else
      fail "fields.xdmf of the frames that fit is missing"
    fi ;;
  static)
    [ -s "$reference/static_states.csv" ] || fail "the undisturbed run ended no hold (the case tests nothing)" ;;
  final_state)
    # Not torn: absent, never a cut last row (it is written to final_state.csv.tmp and
    # renamed once complete), and no temporary file left on the full disk.
    [ ! -e "$out/final_state.csv.tmp" ] || fail "a partial final_state.csv.tmp was left on the full disk"
    [ ! -e "$out/final_state.csv" ] || fail "final_state.csv was left although it could not be written whole"
    [ -s "$reference/final_state.csv" ] || fail "the undisturbed run wrote no final_state.csv (the case tests nothing)"
    rows="$rows; no torn final_state.csv" ;;
esac
[ ! -e "$out/checkpoint.h5.tmp" ] || fail "a temporary file was left"
log="$work/run.log" STATUS=$fault_status ok "disk full ($DISK) during $what on $ranks rank(s), stopped in ${seconds%???????} s, $rows"
