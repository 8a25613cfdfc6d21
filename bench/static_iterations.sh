#!/usr/bin/env bash
# The static solver's work per load step (-solver static, docs/options_run.md "Static
# solver") on the plate with a hole (examples/plate_hole.yaml), against the spacing
# (1 rank) and the rank count (at one spacing). Counts only, no timings: per load step the
# stretch reached, the Newton iterations, the Krylov iterations (the predictor's solve
# included; -ksp_converged_reason) and the tangents assembled (one multigrid set-up each;
# -info :pc), and how far the static states (probe and reactions) of each rank count are
# from 1 rank's, relative. Prints a markdown table; docs/performance.md section 6.
#   bench/static_iterations.sh [BAPD] [DX_LIST] [RANK_DX] [RANK_LIST]
# (defaults: build/bapd, "0.002 0.001 0.0005" m on 1 rank, 0.001 m on "1 2 3 4" ranks;
# the runs in ${BAPD_BENCH_DIR:-/tmp/bapd_static_iterations}).
set -uo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bapd="${1:-$root/build/bapd}"
[[ $bapd == /* ]] || bapd="$PWD/$bapd" # the runs are made in $work
dx_list="${2:-0.002 0.001 0.0005}"
rank_dx="${3:-0.001}"
rank_list="${4:-1 2 3 4}"
work="${BAPD_BENCH_DIR:-/tmp/bapd_static_iterations}"
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1

run() { # RANKS DX: the run's log in dx<DX>_n<RANKS>.log, its output in the directory of that name
  local name="dx${2}_n${1}"
  mpiexec -n "$1" "$bapd" -options_file_yaml "$root/examples/plate_hole.yaml" -body_dx "$2" -solver static \
    -ksp_converged_reason -info :pc -progress_wall_interval 0 -output_dir "$name" > "$name.log" 2>&1 ||
    { echo "bench: $name failed (see $work/$name.log)"; return 1; }
}
runs=() failed=0
for dx in $dx_list; do run 1 "$dx" && runs+=("1 $dx") || failed=1; done
for n in $rank_list; do
  [ "$n" = 1 ] && [[ " $dx_list " == *" $rank_dx "* ]] && continue
  run "$n" "$rank_dx" && runs+=("$n $rank_dx") || failed=1
done

/usr/bin/python3 - "$rank_dx" "${runs[@]}" <<'PY'
import csv, re, sys
rank_dx, runs = sys.argv[1], [r.split() for r in sys.argv[2:]]
def steps(name):
    """Per load step: stretch, Newton, Krylov, tangents; a cut back step's work is its own row."""
    rows, krylov, tangents = [], 0, 0
    for line in open(f"{name}.log"):
        if m := re.search(r"Linear solve converged due to \w+ iterations (\d+)", line):
            krylov += int(m.group(1))
        elif line.startswith("[0] <pc> PCSetUp_MG(): Using outer operators"):
            tangents += 1  # one multigrid set-up per tangent assembled
        elif m := re.match(r"Load step \d+: stretch ([\d.]+), (\d+) Newton", line):
            rows.append((f"{float(m.group(1)):g}", m.group(2), krylov, tangents))
            krylov = tangents = 0
        elif m := re.match(r"Load step to stretch ([\d.]+) did not converge", line):
            rows.append((f"{float(m.group(1)):g} (cut back)", "-", krylov, tangents))
            krylov = tangents = 0
    return rows
def states(name):
    rows = list(csv.DictReader(open(f"{name}/static_states.csv")))
    return [[float(v) for k, v in r.items() if k.endswith("_m") or k.endswith("_N")] for r in rows]
print("| dx (mm) | ranks | points | per load step, stretch: Newton / Krylov / tangents | all load steps | static states from 1 rank's |")
print("|---|---|---|---|---|---|")
for n, dx in runs:
    name = f"dx{dx}_n{n}"
    rows = steps(name)
    points = re.search(r"Body: (\d+) points", open(f"{name}.log").read())
    per = "; ".join(f"{s}: {a} / {k} / {t}" for s, a, k, t in rows)
    total = (f"{sum(int(a) for _, a, _, _ in rows if a != '-')} / {sum(k for _, _, k, _ in rows)}"
             f" / {sum(t for *_, t in rows)}")
    summary = re.search(r"(\d+) Newton iterations, (\d+) Krylov iterations .*?(\d+) tangents", open(f"{name}.log").read())
    cut = any(a == "-" for _, a, _, _ in rows)  # a cut back step's Newton iterations are not printed
    if summary and [g for i, g in enumerate(summary.group(1, 2, 3)) if i or not cut] != total.split(" / ")[cut:]:
        print(f"bench: {name}: the per-step counts {total} miss the summary's {'/'.join(summary.group(1, 2, 3))}", file=sys.stderr)
    diff = ""
    if dx == rank_dx and n != "1" and ["1", dx] in runs:
        a, b = states(f"dx{dx}_n1"), states(name)
        diff = f"{max(abs(y / x - 1) for ra, rb in zip(a, b) for x, y in zip(ra, rb) if x != 0):.1e}"
    print(f"| {1e3 * float(dx):g} | {n} | {points.group(1) if points else '?'} | {per} | {total} | {diff} |")
PY
exit $((failed || $?))
