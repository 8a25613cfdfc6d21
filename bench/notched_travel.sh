#!/usr/bin/env bash
# Time to solution of the notched scene against the crack-phase step control:
# runs the notched pure-shear scene once per setting of the step control, one after the
# other, and prints one row per run: steps, steps shortened by the travel limit, the
# shortest step, CPU and wall time, and the crack result (onset = the stretch with 20
# broken bonds, peak nominal stress, broken bonds, and check_notched.py's path test:
# straight along the notch line, through the width, symmetric). Only the ratios of
# runs in one call and the counts are figures (a shared machine's load inflates wall).
#
#   bench/notched_travel.sh [--paper] [--ranks N] [--exe BAPD] [--out DIR] SETTING...
#   bench/notched_travel.sh 0.1 0.2 0.3 off        # -time_step_travel 0.1, 0.2, 0.3, 0
#   bench/notched_travel.sh --paper --ranks 2 0.1  # the paper grid (dx = 1/3 mm, 70 mm, to stretch 5)
#
# A SETTING is a number (-time_step_travel X), "off" (-time_step_travel 0), "auto" (no
# option: the solver's choice) or any options in quotes ("-time_step_travel 0.2 -damping 400").
# The short scene is tests/validation/notched_short.sh's (dx = 0.5 mm, 35 mm wide, to
# stretch 3.4), on 1 rank unless --ranks; the path test is check_notched.py's, which
# knows the short grid only (--paper prints onset, peak and broken bonds).
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
exe="$here/build/bapd"
out=/tmp/bapd-notched-travel
ranks=1
paper=0
settings=()
while (($#)); do
  case "$1" in
    --paper) paper=1; shift ;;
    --ranks) ranks="$2"; shift 2 ;;
    --exe) exe="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    -h|--help) sed -n '2,19p' "$0"; exit 0 ;;
    *) settings+=("$1"); shift ;;
  esac
done
((${#settings[@]})) || settings=(auto)
mkdir -p "$out"
scene=(-options_file_yaml "$here/examples/notched_pure_shear.yaml" -output_interval 10 -progress_interval 1000000 -output_final_state)
((paper)) || scene+=(-body_dx 0.0005 -body_width 0.035 -body_notches 0.025,0.005,0.035,0.005
                     -probe_notch_mouth_top_at 0.035,0.0052 -probe_notch_mouth_bottom_at 0.035,0.0048
                     -load_schedule 0,1,0.4,3.4)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
printf "%-28s %6s %7s %9s %8s %8s %7s %8s %7s %6s %s\n" setting steps travel "shortest" cpu_s wall_s onset peak_Pa broken rc path
k=0
for s in "${settings[@]}"; do
  case "$s" in
    auto) opts=() ;;
    off) opts=(-time_step_travel 0) ;;
    -*) read -r -a opts <<< "$s" ;;
    *) opts=(-time_step_travel "$s") ;;
  esac
  dir="$out/run$k"; k=$((k + 1))
  rm -rf "$dir"
  /usr/bin/time -f "%U %S %e" -o "$dir.time" mpiexec -n "$ranks" --bind-to none "$exe" "${scene[@]}" "${opts[@]}" -output_dir "$dir" > "$dir.log" 2>&1
  rc=$?
  read -r user sys wall < <(tail -n 1 "$dir.time" 2>/dev/null) || { user=0; sys=0; wall=0; }  # (time adds a "Command exited" line first on failure)
  path="-"
  if ((!paper)) && ((rc == 0)); then
    /usr/bin/python3 "$here/tests/validation/check_notched.py" "$dir" "$dir.log" > "$dir.check" 2>&1 && path=ok || path=FAIL
  fi
  /usr/bin/python3 - "$dir" "$dir.log" "$s" "$user" "$sys" "$wall" "$rc" "$path" <<'EOF'
import csv, re, sys
run, log, setting, user, sys_, wall, rc, path = sys.argv[1:]
text = open(log).read()
steps = re.search(r"(?:Finished|Stopped[^:]*): (\d+) steps", text)
travel = re.search(r"(\d+) by the travel limit", text)
shortest = re.search(r"the shortest [0-9.e+-]+ s = ([0-9.e+-]+) x", text)
try:
    rows = list(csv.DictReader(open(f"{run}/history.csv")))  # a stopped run's rows too: onset and peak before the stop
except OSError:
    rows = []
onset, peak, broken = float("nan"), float("nan"), 0
if rows:
    stretch = [float(r["stretch"]) for r in rows]
    stress = [float(r["top_nominal_stress_Pa"]) for r in rows]
    bb = [int(r["broken_bonds"]) for r in rows]
    onset = next((s for s, b in zip(stretch, bb) if b >= 20), float("nan"))
    peak, broken = max(stress), bb[-1]
print(f"{setting:28s} {steps.group(1) if steps else '-':>6s} {travel.group(1) if travel else '0':>7s} {shortest.group(1) if shortest else '-':>9s} "
      f"{float(user) + float(sys_):8.1f} {float(wall):8.1f} {onset:7.3f} {peak:8.0f} {broken:7d} {rc:>6s} {path}")
EOF
done
