#!/usr/bin/env bash
# The cost of the stable-step estimate at rest, before the first step: each scene set up
# (-end_step 0: the run stops before step 1) with the Krylov search (-time_step_estimate
# krylov, the default) and with the 60 power iterations it replaced (power), side by
# side in one invocation, one rank. Prints a markdown table: the force evaluations of the
# estimate (a deterministic count), lambda_max of each, and the wall and CPU time of each
# set-up (user + system, /usr/bin/time); the difference of the two set-ups is the
# estimates' difference, the rest of the set-up being the same.
#   bench/startup_estimate.sh [OUTPUT_DIR] [SCENE ...]
# (default /tmp/bapd_startup_estimate, scenes sheet and block_3d: the pure-shear sheet,
# 4 480 points, and the block with a hole of tests/data/scenes/block_3d.yaml at dx =
# 0.17 mm, 88 620 points; also plate, the plate with a hole at dx = 0.5 mm.)
# Measured (docs/stability.md section 3): the block's set-up 81 s of CPU with power
# (61 evaluations), 30 s with krylov (16).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-/tmp/bapd_startup_estimate}"
exe="${BAPD_EXE:-$here/build/bapd}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
shift || true
names=("$@")
((${#names[@]})) || names=(sheet block_3d)
mkdir -p "$out"
declare -A scenes=(
  [sheet]="-options_file_yaml $here/examples/pure_shear.yaml"
  [plate]="-options_file_yaml $here/examples/plate_hole.yaml -body_dx 0.0005"
  [block_3d]="-options_file_yaml $here/tests/data/scenes/block_3d.yaml -body_dx 0.00017"
)
echo "| scene | points | method | force evaluations | lambda_max (1/s^2) | set-up wall (s) | set-up CPU (s) |"
echo "|---|---|---|---|---|---|---|"
for name in "${names[@]}"; do
  for method in power krylov; do
    log="$out/${name}_$method.log"
    rm -rf "$out/${name}_$method"
    # shellcheck disable=SC2086 # the scene is a list of words
    /usr/bin/time -f "cpu %U %S" -o "$out/${name}_$method.cpu" "$exe" ${scenes[$name]} -end_step 0 -time_step_estimate "$method" \
      -progress_wall_interval 0 -output_dir "$out/${name}_$method" > "$log" 2>&1 || true
    /usr/bin/python3 - "$log" "$out/${name}_$method.cpu" "$name" "$method" <<'PY'
import re, sys
text, name, method = open(sys.argv[1]).read(), sys.argv[3], sys.argv[4]
m = re.search(r"cpu (\S+) (\S+)", open(sys.argv[2]).read())
cpu = float(m.group(1)) + float(m.group(2)) if m else float("nan")
s = re.search(r"^Stable time step \S+ s \(.*?, (\d+) force evaluations, lambda_max = (\S+) 1/s\^2\)", text, re.M)
w = re.search(r"^Finished: .*wall (\S+) s", text, re.M)
p = re.search(r"^Body: (\d+) points", text, re.M)
print(f"| {name} | {p.group(1) if p else '?'} | {method} | {s.group(1) if s else '?'} | {s.group(2) if s else '?'} | "
      f"{w.group(1) if w else '?'} | {cpu:.1f} |")
PY
  done
done
