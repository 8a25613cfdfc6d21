#!/usr/bin/env bash
# A restart whose output directory holds newer results than its checkpoint (an older
# copy of a checkpoint restarted in place): refused before any step with one `bapd:
# error:` line naming the checkpoint, the newer results and the fix, and every file left
# as it was. A restart in place from the directory's own newest checkpoint goes on, also
# when a killed run left rows after it (written again, as the uninterrupted run did);
# -restart_discard_newer drops the newer results and continues: the rows up to its end
# are the uninterrupted run's.
#   restart_newer.sh RANKS
source "$BAPD_SOURCE_DIR/tests/faults/common.sh"
ranks="$1"
((ranks == 1)) && export OMPI_MCA_odls_base_sigkill_timeout=0 # (bad_input.sh explains)
work="faults_restart_newer_np$ranks"
rm -rf "$work" && mkdir -p "$work" || exit 1
out="$work/out"
# Steps 0 to 20, a checkpoint at 20 (kept as a backup copy), then on to 40 in place;
# rows every 5 steps only (-output_history_rows 0), so that their counts below are known.
bounded "$work/first.log" "$ranks" "$TINY" -end_step 20 -checkpoint_interval 20 -output_interval 5 -output_history_rows 0 -output_fields \
  -output_fields_interval 10 -output_dir "$out"
((STATUS == 0)) || fail "the first run failed"
cp "$out/checkpoint.h5" "$out/backup_step20.h5"
bounded "$work/second.log" "$ranks" -restart "$out/checkpoint.h5" -end_step 40
((STATUS == 0)) || fail "the restart in place from the newest checkpoint was refused"
cp -r "$out" "$work/before"
unchanged() {
  local f
  for f in history.csv checkpoint.h5 fields.xdmf fields/step_00000030.h5 fields/step_00000040.h5; do
    cmp -s "$work/before/$f" "$1/$f" || fail "$f was changed by the refused restart"
  done
}

# The older copy: refused, naming the newer rows, checkpoint and field files.
bounded "$work/backup.log" "$ranks" -restart "$out/backup_step20.h5" -end_step 30
stopped_cleanly "-restart $out/backup_step20.h5 is the state at step 20" "history.csv has 4 row(s) after step 20 (up to step 40)" \
  "checkpoint.h5 is at step 40" "2 field file(s) after step 20 (up to fields/step_00000040.h5)" "-restart $out/checkpoint.h5" "-output_dir" "-restart_discard_newer"
grep -q "^step " "$log" && fail "steps were taken"
unchanged "$out"
ok "an older checkpoint restarted in place, $ranks rank(s)"

# A run killed after its last checkpoint: rows and a field file after it, the checkpoint
# the directory's own and the newest. The usual restart: it goes on, says so, and writes
# those rows again as the uninterrupted run did.
cp -r "$work/before" "$work/killed" && cp "$out/backup_step20.h5" "$work/killed/checkpoint.h5"
bounded "$work/killed.log" "$ranks" -restart "$work/killed/checkpoint.h5" -output_dir "$work/killed" -end_step 40
((STATUS == 0)) || fail "the restart from the directory's own newest checkpoint was refused: $(grep error: "$work/killed.log")"
grep -q "holds results after its checkpoint's step 20 (history.csv has 4 row(s) after step 20" "$work/killed.log" || fail "no note on the rows written again"
cmp -s "$work/before/history.csv" "$work/killed/history.csv" || fail "the continuation's history.csv differs from the uninterrupted run's"
ok "rows after the directory's own newest checkpoint written again, $ranks rank(s)"

# -restart_discard_newer: continues from step 20 to 30, as the uninterrupted run did.
bounded "$work/discard.log" "$ranks" -restart "$out/backup_step20.h5" -end_step 30 -restart_discard_newer
((STATUS == 0)) || fail "-restart_discard_newer did not continue"
whole_rows "$out/history.csv"
[ "$(tail -1 "$out/history.csv" | cut -d, -f1)" = 30 ] || fail "history.csv does not end at step 30"
same_prefix "$out/history.csv" "$work/before/history.csv"
[ ! -e "$out/fields/step_00000040.h5" ] || fail "the discarded field file of step 40 is still there"
grep -q "step_00000040" "$out/fields.xdmf" && fail "fields.xdmf lists the discarded step 40"
echo "ok   -restart_discard_newer continues from step 20 to the uninterrupted run's rows"
