#!/usr/bin/env bash
# The static solver's crack on 1 and 2 ranks: the notched pure-shear sheet (dx = 1 mm,
# Gamma = 165 J/m^2) pulled past its first break and on while the crack grows (to stretch
# 3.1: 40 bonds broken, in 8 re-equilibrations). The same history rows with
# the same broken-bond counts, the same broken bonds (broken_bonds.csv), and the final
# displacement field within 1e-10 of the largest (each Newton solve ends at 1e-10 of the
# reactions; the ranks' partial sums in the Krylov solves differ at round-off).
#   crack_ranks_static.sh  (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
. "$(dirname "$0")/common.sh" static_crack_ranks
notch=(-options_file_yaml "$src/examples/notched_pure_shear_gamma.yaml" -body_dx 0.001 -body_width 0.03
       -body_notches 0.02,0.005,0.03,0.005 -probe_notch_mouth_top_at 0.03,0.0052 -probe_notch_mouth_bottom_at 0.03,0.0048
       -progress_interval 1000000 -load_schedule 0,1,0.525,3.1 -solver static -output_final_state)
for n in 1 2; do
  timeout 300 mpiexec -n $n "$BAPD_EXE" "${notch[@]}" -output_dir np$n > np$n.log 2>&1 || { fail "$n rank(s): exit $?"; tail -5 np$n.log; }
done
/usr/bin/python3 - <<'PY' || failures=$((failures + 1))
import csv
def rows(n):
    return [(r["step"], r["stretch"], int(r["broken_bonds"])) for r in csv.DictReader(open(f"np{n}/history.csv"))]
def field(n):
    return {r["natural_id"]: (float(r["ux_m"]), float(r["uy_m"])) for r in csv.DictReader(open(f"np{n}/final_state.csv"))}
one, two = rows(1), rows(2)
bonds = [open(f"np{n}/broken_bonds.csv").read() for n in (1, 2)]
f1, f2 = field(1), field(2)
scale = max(abs(u) for p in f1.values() for u in p)
worst = max(abs(a - b) for k in f1 for a, b in zip(f1[k], f2[k])) / scale
broken = one[-1][2]
print(f"{len(one)} and {len(two)} history rows, {broken} and {two[-1][2]} bonds broken at the end; "
      f"displacement field within {worst:.1e} of the largest")
ok = len(one) == len(two) and [r[2] for r in one] == [r[2] for r in two] and broken >= 20 and bonds[0] == bonds[1] and worst < 1e-10
if not ok:
    print("FAIL the ranks disagree (or the crack did not grow: fewer than 20 bonds broken)")
raise SystemExit(0 if ok else 1)
PY
finish crack_ranks_static
