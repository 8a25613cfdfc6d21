#!/usr/bin/env bash
# Time to solution, one git revision against another: builds bapd at both
# revisions, runs the paper's three scenes with each, alternating (A B A B ...: a
# shared machine's load falls on both alike), and prints one table per scene with the
# figure of merit (CPU and wall time, steps, ghost exchanges = force evaluations plus
# one a step with failure, CPU time per step per point) and the ratio new / old. A scene more than 10 % slower (CPU time, the best of
# the repeats) is flagged SLOWER and the script exits 1.
#
#   bench/compare_revisions.sh OLD NEW              # e.g. main HEAD, or two commit ids
#   bench/compare_revisions.sh --quick OLD NEW      # one repeat, pure shear cut to 0.4 s
#   bench/compare_revisions.sh --exe-old A --exe-new B   # two bapd executables, no build
#
# Options: --repeats N (default 2), --ranks N (default 1: CPU time of one core, which
# a shared machine inflates least), --out DIR (default /tmp/bapd-revisions/OLD-NEW),
# --scenes LIST (plate,pure_shear,notched,notched_gamma), --threshold 1.10.
#
# The scenes (what is timed is what docs/validation.md checks):
#   plate       examples/plate_hole.yaml by the fast route (plate_hole_fast.yaml),
#               dx = 1 mm, whole run
#   pure_shear  examples/pure_shear.yaml, whole run (to stretch 5.125)
#   notched     the short notched sheet of tests/validation/notched_short.sh (dx = 0.5
#               mm, 35 mm wide), pulled at 6 /s to stretch 3.4: the crack starts and runs through.
#               The paper grid (dx = 1/3 mm, to stretch 5) takes ~10 min per run here,
#               too heavy for a side-by-side on a shared 2-core machine.
#   notched_gamma  the same sheet with examples/notched_pure_shear_gamma.yaml's fracture
#               energy (Gamma = 165 J/m^2), to stretch 3.15: the onset (near 3.0) and the
#               first millimetres of the crack (not in the default list).
# Each revision is exported with `git archive` into OUT/src-SHA and built there
# (Release, the bapd target only; a build already there is reused). Outputs of both
# revisions are compared too: "identical" means history.csv is the same byte for byte.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
PY=/usr/bin/python3
repeats=2
ranks=1
quick=0
threshold=1.10
scenes="plate,pure_shear,notched"
out=""
exe_old=""
exe_new=""
revs=()
while (($#)); do
  case "$1" in
    --quick) quick=1; repeats=1; shift ;;
    --repeats) repeats="$2"; shift 2 ;;
    --ranks) ranks="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --scenes) scenes="$2"; shift 2 ;;
    --threshold) threshold="$2"; shift 2 ;;
    --exe-old) exe_old="$2"; shift 2 ;;
    --exe-new) exe_new="$2"; shift 2 ;;
    -h|--help) sed -n '2,31p' "$0"; exit 0 ;;
    -*) echo "compare_revisions.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
    *) revs+=("$1"); shift ;;
  esac
done
if [ -z "$exe_old" ] || [ -z "$exe_new" ]; then
  if ((${#revs[@]} != 2)); then
    echo "compare_revisions.sh: give two revisions (OLD NEW) or --exe-old and --exe-new (see --help)" >&2
    exit 2
  fi
fi

build_revision() { # rev -> path of its bapd
  local rev="$1" sha src
  sha=$(git -C "$here" rev-parse --short=10 "$rev^{commit}") || { echo "compare_revisions.sh: no revision $rev" >&2; exit 2; }
  src="$out/src-$sha"
  if [ ! -x "$src/build/bapd" ]; then
    mkdir -p "$src"
    git -C "$here" archive "$sha" | tar -x -C "$src"
    cmake -S "$src" -B "$src/build" -DCMAKE_BUILD_TYPE=Release >"$src/configure.log" 2>&1 ||
      { tail -20 "$src/configure.log" >&2; exit 1; }
    cmake --build "$src/build" -j "$(nproc)" --target bapd >"$src/build.log" 2>&1 ||
      { tail -30 "$src/build.log" >&2; exit 1; }
  fi
  echo "$src/build/bapd"
}

if [ -z "$exe_old" ]; then
  out="${out:-/tmp/bapd-revisions/${revs[0]//\//_}-${revs[1]//\//_}}"
  mkdir -p "$out"
  echo "building ${revs[0]} and ${revs[1]} in $out (a few minutes each)"
  exe_old=$(build_revision "${revs[0]}")
  exe_new=$(build_revision "${revs[1]}")
  label_old="${revs[0]}"; label_new="${revs[1]}"
else
  out="${out:-/tmp/bapd-revisions/executables}"
  mkdir -p "$out"
  label_old="$exe_old"; label_new="$exe_new"
fi

ex="$here/examples"
scene_args() { # scene -> bapd arguments (the scene file first)
  case "$1" in
    plate) echo "$ex/plate_hole.yaml -options_file_yaml $ex/plate_hole_fast.yaml" ;;
    pure_shear)
      if ((quick)); then echo "$ex/pure_shear.yaml -load_schedule 0,1,0.4,2.65"
      else echo "$ex/pure_shear.yaml"; fi ;;
    notched)
      echo "$ex/notched_pure_shear.yaml -body_dx 0.0005 -body_width 0.035 -body_notches 0.025,0.005,0.035,0.005" \
           "-probe_notch_mouth_top_at 0.035,0.0052 -probe_notch_mouth_bottom_at 0.035,0.0048 -load_schedule 0,1,0.4,3.4" ;;
    notched_gamma)
      echo "$ex/notched_pure_shear_gamma.yaml -body_dx 0.0005 -body_width 0.035 -body_notches 0.025,0.005,0.035,0.005" \
           "-probe_notch_mouth_top_at 0.035,0.0052 -probe_notch_mouth_bottom_at 0.035,0.0048 -load_schedule 0,1,0.358,3.15" ;;
    *) echo "compare_revisions.sh: unknown scene $1 (plate, pure_shear, notched, notched_gamma)" >&2; exit 2 ;;
  esac
}

echo "old: $label_old ($exe_old)"
echo "new: $label_new ($exe_new)"
echo "load at start: $(cut -d' ' -f1-3 /proc/loadavg)" | tee "$out/load.txt"
IFS=, read -r -a scene_list <<<"$scenes"
for scene in "${scene_list[@]}"; do
  read -r -a args <<<"$(scene_args "$scene")"
  for ((r = 1; r <= repeats; r++)); do
    for side in old new; do
      exe=$exe_old; [ "$side" = new ] && exe=$exe_new
      "$PY" "$here/bench/bapd_run.py" --exe "$exe" --ranks "$ranks" --out "$out/runs" \
        --label "${scene}_${side}_$r" -- "${args[@]}" -output_dir "$out/runs/o_${scene}_${side}_$r" \
        -progress_interval 1000000 -log_view || true
    done
  done
done
"$PY" "$here/bench/revisions.py" "$out/runs" --scenes "$scenes" --repeats "$repeats" --threshold "$threshold" \
  --old "$label_old" --new "$label_new" | tee "$out/summary.md"
