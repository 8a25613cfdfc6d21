#!/usr/bin/env bash
# A restart writes the history rows the uninterrupted run writes, the rows by load
# (-output_history_rows) included, whichever step it continues from: a step that was a
# row by load (its row is kept) and one that was not (the end-of-run row of the first
# part is dropped and the continuation goes on). Each first part ends with a
# checkpoint written after its end-of-run row (-checkpoint_interval longer than the
# run: the checkpoint at the end), so that the checkpoint holds that row. history.csv
# is then the uninterrupted run's byte for byte, on 2 and on 3 ranks.
set -euo pipefail
source "$BAPD_SOURCE_DIR/tests/mpi/restart/common.sh"
work="restart_history_rows"
rm -rf "$work"; mkdir -p "$work"
# No failure, no static test: -output_interval far beyond the run, so that every row
# after step 0 is a row by load or the last one. 0.2 s / 100 = 2 ms a row, ~9 steps.
scene=("${NOTCHED[@]}" -load_schedule 0,1,0.2,1.6 -output_interval 100000)
M=120
run 2 "$work/whole" "${scene[@]}" -end_step $M
# A step with a row by load, and the step after it (none: rows are ~9 steps apart).
read -r by_load not_row < <($PYTHON - "$work/whole/history.csv" $M << 'PY'
import csv, sys
steps = [int(r["step"]) for r in csv.DictReader(open(sys.argv[1]))]
M = int(sys.argv[2])
s = next(s for s in steps if M // 3 < s < M - 10 and s + 1 not in steps)
print(s, s + 1)
PY
)
echo "continuing from step $by_load (a row by load) and step $not_row (no row)"
for N in $by_load $not_row; do
  run 2 "$work/first_$N" "${scene[@]}" -end_step $N -checkpoint_interval 100000
  [ -f "$work/first_$N/checkpoint.h5" ] || fail "no checkpoint at the end of the first part ($N steps)"
  grep -q "^$N," "$work/first_$N/history.csv" || fail "the first part has no row at its last step $N"
  for ranks in 2 3; do
    out="$work/second_${N}_np$ranks"
    run $ranks "$out" -restart "$work/first_$N/checkpoint.h5" -end_step $M
    grep -q "Restart from $work/first_$N/checkpoint.h5: step $N" "$out.log" || fail "no restart line in $out.log"
    cmp "$work/whole/history.csv" "$out/history.csv" || fail "$out/history.csv differs from the uninterrupted run's"
  done
  python3 "$BAPD_SOURCE_DIR/tests/mpi/compare_runs.py" --tolerance 0 "$work/whole" "$work/second_${N}_np2" "$work/second_${N}_np3"
done
rows=$(($(wc -l < "$work/whole/history.csv") - 1))
((rows >= M / 10)) || fail "$rows rows over $M steps: the rows by load are missing"
echo "restart history rows: the uninterrupted run's ($rows rows)"
