#!/usr/bin/env bash
# A restart in place that adds a probe keeps history.csv's earlier rows: the new header,
# the earlier rows with their values under the same column names and nan in the new
# probe's columns, then the continuation's rows.
# (Rows every -output_interval steps only: -output_history_rows 0.)
#   restart_columns.sh RANKS
source "$BAPD_SOURCE_DIR/tests/faults/common.sh"
ranks="$1"
((ranks == 1)) && export OMPI_MCA_odls_base_sigkill_timeout=0 # (bad_input.sh explains)
work="faults_restart_columns_np$ranks"
rm -rf "$work" && mkdir -p "$work" || exit 1
out="$work/out"
bounded "$work/first.log" "$ranks" "$TINY" -end_step 20 -checkpoint_interval 20 -output_interval 5 -output_history_rows 0 -output_dir "$out"
((STATUS == 0)) || fail "the first run failed"
cp "$out/history.csv" "$work/first_history.csv"
bounded "$work/second.log" "$ranks" -restart "$out/checkpoint.h5" -end_step 40 -probes centre -probe_centre_at 0.005,0.005
((STATUS == 0)) || fail "the restart with a new probe failed"
whole_rows "$out/history.csv"
"$PYTHON" - "$work/first_history.csv" "$out/history.csv" << 'PY' || fail "history.csv lost or changed the rows before the restart"
import csv, math, sys
first = list(csv.DictReader(open(sys.argv[1])))
rows = list(csv.DictReader(open(sys.argv[2])))
steps = [int(r["step"]) for r in rows]
assert steps == list(range(0, 41, 5)), steps
for old, new in zip(first, rows):
    assert all(new[k] == v for k, v in old.items()), f"step {old['step']}: a value changed"
    assert math.isnan(float(new["centre_ux_m"])) and math.isnan(float(new["centre_uy_m"])), "no nan before the probe"
for r in rows[len(first):]:
    assert math.isfinite(float(r["centre_uy_m"])), f"step {r['step']}: no probe value"
print(f"{len(first)} earlier rows kept, {len(rows) - len(first)} with the probe")
PY
grep -q "its 5 earlier row(s) are kept, with nan in the new column(s) centre_ux_m, centre_uy_m" "$log" || fail "the run does not say what it did with the earlier rows"
echo "ok   a probe added on restart, $ranks rank(s): the earlier rows kept"
