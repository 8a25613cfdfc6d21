#!/usr/bin/env bash
# The cost of re-estimating the stable step: each scene run side by side
# with the step fixed at rest (-time_step_reestimate 0) and with the default
# re-estimate, one rank, the same number of steps. Prints a markdown table: the force
# evaluations of the dynamics (one a step) and of the re-estimates, a deterministic
# count whose ratio is the cost without the machine's noise; the wall time of both
# runs and their CPU time (user + system, /usr/bin/time: less sensitive to the load of
# a shared machine than the wall time), and the ratio of the two CPU times; the time the re-estimates took (-time_step_monitor, measured inside the run,
# so it does not depend on the load of the machine the way the difference of two wall
# times does) and its share of the run; and the step at the end.
#   bench/time_step.sh [STEPS] [OUTPUT_DIR] [SCENE ...]
# (default 1000 steps, /tmp/bapd_time_step, scenes plate plate_Jm8 notched_short; also
# notched (the example, hundreds of seconds), pure_shear, and plate_Jm8_indicator (the
# search called by the stiffening indicator, -time_step_reestimate_indicator), and plate_Jm8_bonds (called by
# the kernel's stiffest bond, -time_step_reestimate_bonds); a STEPS past a scene's end
# runs it whole).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
steps="${1:-1000}"
out="${2:-/tmp/bapd_time_step}"
exe="${BAPD_EXE:-$here/build/bapd}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
shift 2 || shift $# || true
names=("$@")
((${#names[@]})) || names=(plate plate_Jm8 notched_short)
mkdir -p "$out"
declare -A scenes=(
  [plate]="-options_file_yaml $here/examples/plate_hole.yaml -options_file_yaml $here/examples/plate_hole_fast.yaml"
  [plate_Jm8]="-options_file_yaml $here/examples/plate_hole.yaml -options_file_yaml $here/examples/plate_hole_fast.yaml -material_Jm 8 -load_schedule 0,1,0.05,1.5,1.05,1.5,1.1,2.0,2.1,2.0"
  [plate_Jm8_indicator]="-options_file_yaml $here/examples/plate_hole.yaml -options_file_yaml $here/examples/plate_hole_fast.yaml -material_Jm 8 -load_schedule 0,1,0.05,1.5,1.05,1.5,1.1,2.0,2.1,2.0 -time_step_reestimate_indicator"
  [plate_Jm8_bonds]="-options_file_yaml $here/examples/plate_hole.yaml -options_file_yaml $here/examples/plate_hole_fast.yaml -material_Jm 8 -load_schedule 0,1,0.05,1.5,1.05,1.5,1.1,2.0,2.1,2.0 -time_step_reestimate_bonds"
  [notched]="-options_file_yaml $here/examples/notched_pure_shear.yaml"
  [notched_short]="-options_file_yaml $here/examples/notched_pure_shear.yaml -body_dx 0.0005 -body_width 0.035 -body_notches 0.025,0.005,0.035,0.005 -probe_notch_mouth_top_at 0.035,0.0052 -probe_notch_mouth_bottom_at 0.035,0.0048 -load_schedule 0,1,0.4,3.4"
  [pure_shear]="-options_file_yaml $here/examples/pure_shear.yaml"
)
echo "| scene | steps | force evaluations: dynamics + re-estimates | re-estimates' share of the evaluations | wall, fixed step (s) | wall, re-estimated (s) | CPU, fixed / re-estimated (s) | CPU ratio per step | re-estimates inside the run (s) | share of the run's time | dt at the end / base |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for name in "${names[@]}"; do
  # shellcheck disable=SC2086 # the scene is a list of words
  /usr/bin/time -f "cpu %U %S" -o "$out/${name}_fixed.cpu" "$exe" ${scenes[$name]} -end_step "$steps" -progress_interval 1000000 \
    -output_dir "$out/${name}_fixed" -time_step_reestimate 0 > "$out/${name}_fixed.log" 2>&1 || true
  # shellcheck disable=SC2086
  /usr/bin/time -f "cpu %U %S" -o "$out/${name}_adaptive.cpu" "$exe" ${scenes[$name]} -end_step "$steps" -progress_interval 1000000 \
    -output_dir "$out/${name}_adaptive" -time_step_monitor > "$out/${name}_adaptive.log" 2>&1 || true
  /usr/bin/python3 - "$out/${name}_fixed.log" "$out/${name}_adaptive.log" "$name" "$out/${name}_fixed.cpu" "$out/${name}_adaptive.cpu" <<'PY'
import re, sys
fixed, adaptive, name = open(sys.argv[1]).read(), open(sys.argv[2]).read(), sys.argv[3]
def cpu(path):
    m = re.search(r"cpu (\S+) (\S+)", open(path).read())
    return float(m.group(1)) + float(m.group(2)) if m else float("nan")
cf, ca = cpu(sys.argv[4]), cpu(sys.argv[5])
def wall(text):
    m = re.search(r"^(?:Finished|Stopped)[^:]*: (\d+) steps.*wall (\S+) s", text, re.M)
    return (int(m.group(1)), float(m.group(2))) if m else (0, float("nan"))
(nf, wf), (na, wa) = wall(fixed), wall(adaptive)
summary = re.search(r"time step: re-estimated \d+ time\(s\) \((\d+) force evaluations, (\S+) s\)", adaptive)
evals, secs = (int(summary.group(1)), float(summary.group(2))) if summary else (0, 0.0)
est = re.findall(r"\((\S+) x base\), next in", adaptive)
ratio = est[-1] if est else "1"
stop = "" if "error:" not in fixed else " (fixed: diverged)"
# Velocity Verlet evaluates the force once a step: the dynamics' evaluations are the steps.
# Per step: a fixed-step run that diverged stopped early.
per = (ca / na) / (cf / nf) if nf and na else float("nan")
print(f"| {name}{stop} | {na} | {na} + {evals} | {100 * evals / (na + evals):.1f} % | {wf:.1f} | {wa:.1f} | {cf:.1f} / {ca:.1f} | {per:.3f} | {secs:.2f} | {100 * secs / wa:.1f} % | {ratio} |")
PY
done
