#!/usr/bin/env bash
# The static solver on 1, 2 and 3 ranks: the same static states within 1e-10 relative
# (each Newton solve ends at 1e-10 of the grips' reactions; the ranks' partial sums in
# the Krylov solves differ at round-off), on the plate with a hole at dx = 4 mm.
#   ranks_static.sh        (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
. "$(dirname "$0")/common.sh" static_ranks
for n in 1 2 3; do
  timeout 600 mpiexec -n $n "$BAPD_EXE" "${plate[@]}" -body_dx 0.004 -solver static -output_final_state -output_dir np$n \
    > np$n.log 2>&1 || fail "$n rank(s): exit $?"
done
/usr/bin/python3 - <<'PY' || failures=$((failures + 1))
import csv
def table(n):
    return [[float(v) for v in r.values()] for r in csv.DictReader(open(f"np{n}/static_states.csv"))]
def points(n):
    return {r["natural_id"]: (float(r["ux_m"]), float(r["uy_m"])) for r in csv.DictReader(open(f"np{n}/final_state.csv"))}
ok = True
one, field = table(1), points(1)
scale = max(abs(u) for p in field.values() for u in p)
for n in (2, 3):
    other, f = table(n), points(n)
    worst = max((abs(a - b) / max(abs(a), 1e-300) for r, s in zip(one, other) for a, b in zip(r, s) if a != 0), default=0)
    worst_field = max(abs(a - b) for k in field for a, b in zip(field[k], f[k])) / scale
    print(f"{n} ranks: static states within {worst:.1e} relative, displacement field within {worst_field:.1e} of the largest")
    ok = ok and len(one) == len(other) == 3 and worst < 1e-10 and worst_field < 1e-10 and field.keys() == f.keys()
if not ok:
    print("FAIL the ranks disagree")
raise SystemExit(0 if ok else 1)
PY
finish ranks_static
