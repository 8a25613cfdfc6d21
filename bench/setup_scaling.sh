#!/usr/bin/env bash
# The set-up's wall time and peak memory against the rank count, -partition_type metis
# (rank 0 builds the whole body and bond graph) and ptscotch (every rank builds a slab
# of the lattice) side by side (docs/performance.md section 4d): a square 2D sheet and a
# 3D block (energy-consistent Gent, delta = 3.015 dx), each run through its set-up only
# (-end_step 0). bapd prints with -log_setup_memory, once the body is distributed and
# every rank's families are built: the set-up's wall time (the slowest rank's) and
# VmHWM of the largest rank, the mean rank and rank 0.
#
#   bench/setup_scaling.sh BAPD [--ranks "1 2 4 8"] [--points-2d 1e6] [--points-3d 2e5]
#                               [--only 2d|3d] [--out DIR]
#
# More ranks than cores run oversubscribed: the memory figures hold, the times are
# comparable only between the two partitioners at one rank count (run side by side).
set -euo pipefail
exe="${1:?usage: setup_scaling.sh BAPD [--ranks LIST] [--points-2d N] [--points-3d N] [--only 2d|3d] [--out DIR]}"
shift
ranks="1 2 4 8" points2d=1e6 points3d=2e5 only="" out="/tmp/bapd-setup-$(date +%Y%m%d-%H%M%S)"
while (($#)); do
  case "$1" in
    --ranks) ranks="$2"; shift 2 ;;
    --points-2d) points2d="$2"; shift 2 ;;
    --points-3d) points3d="$2"; shift 2 ;;
    --only) only="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
    *) echo "setup_scaling.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
mkdir -p "$out"
GENT=(-material_mu 4.55e3 -material_Jm 162.6 -material_bulk_ratio 100 -material_density 1000 -horizon_factor 3.015
      -end_step 0 -output_interval 100000 -progress_interval 100000 -log_setup_memory)
# A square sheet of side 0.1 m with sqrt(N) cells a side, gripped top and bottom (its
# grips extrude 3 rows each); a cube of side 0.01 m with cbrt(N) cells a side, x- held, x+ pulled.
sheet() {
  local dx; dx=$(/usr/bin/python3 -c "print(0.1 / round($1 ** 0.5))")
  echo -body_width 0.1 -body_height 0.1 -body_thickness 0.001 -body_dx "$dx" \
    -load_sets top,bottom -load_top_region top -load_top_x fixed -load_top_y stretch \
    -load_bottom_region bottom -load_bottom_x fixed -load_bottom_y fixed -load_schedule 0,1,1,1.1
}
block() {
  local dx; dx=$(/usr/bin/python3 -c "print(0.01 / round($1 ** (1 / 3)))")
  echo -body_dimension 3 -body_dx "$dx" -body_shapes cube -body_cube_type box -body_cube_box 0,0,0,0.01,0.01,0.01 \
    -load_sets left,right -load_left_region x- -load_left_x fixed -load_left_y fixed -load_left_z fixed \
    -load_right_region x+ -load_right_x stretch -load_right_y fixed -load_right_z fixed -load_schedule 0,1,1,1.1
}
printf "%-5s %10s %5s %-9s %9s %11s %9s %10s %10s\n" body points ranks partition "set-up s" "largest MB" "mean MB" "rank 0 MB" "edge cut"
for body in 2d 3d; do
  [ -z "$only" ] || [ "$only" = "$body" ] || continue
  if [ "$body" = 2d ]; then read -ra scene <<<"$(sheet "$points2d")"; else read -ra scene <<<"$(block "$points3d")"; fi
  for n in $ranks; do
    for type in metis ptscotch; do
      log="$out/${body}_np${n}_$type.log"
      mpiexec -n "$n" --oversubscribe --bind-to none "$exe" "${GENT[@]}" "${scene[@]}" -partition_type "$type" \
        -output_dir "$out/${body}_np${n}_$type" > "$log" 2>&1 || { tail -5 "$log"; echo "setup_scaling.sh: $log failed" >&2; exit 1; }
      /usr/bin/python3 - "$log" "$body" "$n" "$type" <<'EOF'
import re, sys
log, body, n, kind = sys.argv[1:]
text = open(log).read()
b = re.search(r"^Body: (\d+) points, \d+ bonds, \d+ rank\(s\); edge cut (\d+)", text, re.M)
s = re.search(r"^Set-up: ([\d.]+) s .*largest rank ([\d.]+) MB, mean rank ([\d.]+) MB, rank 0 ([\d.]+) MB", text, re.M)
print(f"{body:<5} {b.group(1):>10} {n:>5} {kind:<9} {s.group(1):>9} {s.group(2):>11} {s.group(3):>9} {s.group(4):>10} {b.group(2):>10}")
EOF
    done
  done
done
