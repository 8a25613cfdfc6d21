#!/usr/bin/env bash
# The output directory deleted during a run: the run notices at the next
# history row (history.csv unlinked: st_nlink 0), stops every rank with one message
# naming the file and exits non-zero; it does not recreate the directory. A single
# field file deleted: fields.xdmf is rewritten without it and the run stops, naming it.
#   output_deleted.sh RANKS
source "$BAPD_SOURCE_DIR/tests/faults/common.sh"
source "$BAPD_SOURCE_DIR/tests/faults/long_scene.sh"
ranks="$1"
work="faults_output_deleted_np$ranks"
rm -rf "$work" && mkdir -p "$work" || exit 1

# The whole directory (with field files every 37 steps, history rows every 10).
start_long "$work/dir.log" "$ranks" -output_dir "$work/out" -output_fields -output_fields_interval 37
# The run may create a file while rm empties the directory ("Directory not empty"):
# delete until it is gone, as a user's rm -rf would have to.
for attempt in 1 2 3 4 5 6 7 8 9 10; do
  rm -rf "$work/out" 2> /dev/null
  [ -e "$work/out" ] || break
done
[ ! -e "$work/out" ] || fail "could not delete $work/out while the run wrote into it"
finish_long
# Whichever write comes first notices: a history row (usually), a field file or the
# directory check before one.
stopped_cleanly "$work/out"
stopped_saying "was deleted during the run|No such file or directory"
[ ! -e "$work/out" ] || fail "the deleted output directory was recreated"
ok "output directory deleted on $ranks rank(s), stopped ${SECONDS_LEFT} s later"

# One field file.
start_long "$work/file.log" "$ranks" -output_dir "$work/out2" -output_fields -output_fields_interval 50
victim=$(ls "$work/out2/fields" | head -1)
rm "$work/out2/fields/$victim"
finish_long
stopped_cleanly "$victim" "was deleted during the run"
grep -q "$victim" "$work/out2/fields.xdmf" && fail "fields.xdmf still lists the deleted $victim"
"$PYTHON" - "$work/out2" << 'PY' || fail "fields.xdmf lists a file that is missing"
import os, re, sys
out = sys.argv[1]
files = set(re.findall(r'>(fields/step_\d+\.h5):', open(f"{out}/fields.xdmf").read()))
missing = [f for f in files if not os.path.exists(f"{out}/{f}")]
assert files and not missing, missing
PY
whole_rows "$work/out2/history.csv"
ok "field file $victim deleted on $ranks rank(s), stopped ${SECONDS_LEFT} s later"
