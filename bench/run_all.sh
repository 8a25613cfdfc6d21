#!/usr/bin/env bash
# Every benchmark of bapd in one command: builds, runs, prints one table.
#
#   bench/run_all.sh                 # everything (about 1.5 h on 2 cores)
#   bench/run_all.sh --quick         # smaller grids, fewer steps (about 15 min)
#   bench/run_all.sh --only kernel,lammps     # some sections only (see SECTIONS below)
#   bench/run_all.sh --report DIR    # print the table of an earlier run again
#
# Options: --build-dir DIR (default build-bench/ next to the repository, or
# $BAPD_BUILD_DIR), --out DIR (default DIR/bench-results/DATE), --ranks N (the
# parallel rank count, default 2), --accuracy-ranks N (ranks of the accuracy runs,
# default 1: their cost is then the CPU time of one core, which a shared machine does
# not inflate; the wall time is recorded too).
#
# SECTIONS (docs/performance.md explains each figure):
#   kernel     BA Gent plane-stress kernel throughput, delta = 2.515/3.015/3.515 dx,
#              1e4..1e6 points (bench/kernel_bench.cpp)
#   lammps     LAMMPS peri/lps on a 3D lattice with the same number of bonds
#   callgrind  instructions, flops and where they go per bond (bench/callgrind_flops.py),
#              and the residual evaluations per bond inside the solver
#   scaling    bapd on 1e5 and 1e6 points, 1 and N ranks: time per step, memory per point
#   scenes     time to solution of the three paper scenes on 1 and N ranks, phase shares
#   partition  METIS edge cut and ghost ratio for 2..1024 parts, 1e6 and 1e7 points
#   accuracy   plate with a hole: error against FEA vs wall time over dx and delta
#
# Installs what it needs first: scripts/install-deps.sh (the project's packages) and
# scripts/bench/install-bench-deps.sh (lammps, valgrind, time: benchmarks only, not in
# install-deps.sh). Numbers on a shared machine are noisy: kernel times are minima of
# thread CPU time, the flop and instruction counts come from callgrind (exact), and
# every bapd run records its CPU utilisation so that a contended run can be spotted.
set -euo pipefail
here="${BAPD_BENCH_ROOT:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}" # (override: to run a copy of this script)
PY=/usr/bin/python3 # numpy/matplotlib live in the system Python
quick=0
only=""
ranks=2
accuracy_ranks=1
build="${BAPD_BUILD_DIR:-$(dirname "$here")/build-bench}"
out=""
report_only=""
while (($#)); do
  case "$1" in
    --quick) quick=1; shift ;;
    --only) only="$2"; shift 2 ;;
    --ranks) ranks="$2"; shift 2 ;;
    --accuracy-ranks) accuracy_ranks="$2"; shift 2 ;;
    --build-dir) build="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --report) report_only="$2"; shift 2 ;;
    -h|--help) sed -n '2,30p' "$0"; exit 0 ;;
    *) echo "run_all.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
done
if [ -n "$report_only" ]; then
  exec "$PY" "$here/bench/report.py" "$report_only"
fi
want() { [ -z "$only" ] || [[ ",$only," == *",$1,"* ]]; }
out="${out:-$build/bench-results/$(date +%Y%m%d-%H%M%S)}"
mkdir -p "$out"
log() { printf '\n=== %s (%s)\n' "$*" "$(date +%H:%M:%S)"; }

log "install and build"
"$here/scripts/install-deps.sh"
"$here/scripts/bench/install-bench-deps.sh"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -DBAPD_BUILD_TESTS=OFF >/dev/null
fi
# (flock: two run_all.sh --only ... at once must not link into the same tree together)
flock "$build/.bench-build.lock" cmake --build "$build" -j "$(nproc)" --target benchmarks >"$out/build.log" 2>&1 ||
  { tail -30 "$out/build.log" >&2; exit 1; }
bench="$build/bench"
bapd="$build/bapd"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

# The machine the figures come from (kept from the first run into this directory;
# later --only runs into it add their start load to loads.txt).
echo "$(date -u +%H:%M:%S) ${only:-all}: load $(cut -d' ' -f1-3 /proc/loadavg)" >>"$out/loads.txt"
if [ ! -f "$out/machine.txt" ]; then
{
  echo "date=$(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "git=$(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo unknown)$(git -C "$here" diff --quiet 2>/dev/null || echo '+dirty')"
  echo "cpu=$(lscpu | sed -n 's/^Model name: *//p')"
  echo "cpu_family=$(lscpu | sed -n 's/^CPU family: *//p')"
  echo "cpu_model=$(lscpu | sed -n 's/^Model: *//p')"
  echo "cores=$(nproc)"
  echo "hypervisor=$(lscpu | sed -n 's/^Hypervisor vendor: *//p')"
  echo "flags_fma=$(grep -qw fma /proc/cpuinfo && echo yes || echo no)"
  echo "flags_avx2=$(grep -qw avx2 /proc/cpuinfo && echo yes || echo no)"
  echo "flags_avx512f=$(grep -qw avx512f /proc/cpuinfo && echo yes || echo no)"
  echo "bogomips=$(lscpu | sed -n 's/^BogoMIPS: *//p')"
  echo "l2=$(lscpu | sed -n 's/^L2 cache: *//p')"
  echo "l3=$(lscpu | sed -n 's/^L3 cache: *//p')"
  echo "memory_gb=$(free -g | awk '/^Mem:/{print $2}')"
  echo "load_at_start=$(cut -d' ' -f1-3 /proc/loadavg)"
  echo "compiler=$(c++ --version | head -1)"
  echo "lammps=$(dpkg-query -W -f='${Version}' lammps 2>/dev/null || echo none)"
  echo "quick=$quick"
  echo "ranks=$ranks"
} >"$out/machine.txt"
"$bench/kernel_bench" --clock >>"$out/machine.txt"
fi
cat "$out/machine.txt"

if ((quick)); then
  sides=(100 316); factors=(2.515 3.015 3.515)
else
  sides=(100 316 1000); factors=(2.515 3.015 3.515)
fi

if want kernel; then
  log "1. force kernel throughput"
  mkdir -p "$out/kernel"
  for side in "${sides[@]}"; do
    reps=10; ((side >= 1000)) && reps=3
    for f in "${factors[@]}"; do
      "$bench/kernel_bench" --side "$side" --factor "$f" --reps "$reps" --table | tee "$out/kernel/side${side}_f${f}.txt"
    done
  done
fi

if want lammps; then
  log "1b. LAMMPS peri/lps on the same number of bonds"
  mkdir -p "$out/lammps"
  for side in "${sides[@]}"; do
    for f in "${factors[@]}"; do
      # n: 3D lattice side (n + 1 atoms a side) with the bond count closest to the 2D one
      read -r n bonds3 bonds2 steps < <("$PY" "$here/bench/lattice_bonds.py" --match "$side" "$f")
      ((quick)) && steps=$(( (steps + 1) / 2 ))
      (cd "$out/lammps" && lmp -in "$here/bench/lammps/in.peri_lps" -var n "$n" -var factor "$f" -var steps "$steps" \
        -log "side${side}_f${f}.log" -screen none)
      printf 'RESULT side=%s factor=%s n=%s bonds3=%s bonds2=%s steps=%s\n' "$side" "$f" "$n" "$bonds3" "$bonds2" "$steps" \
        >>"$out/lammps/side${side}_f${f}.log"
      grep -E "^Loop time|CPU use|^Pair " "$out/lammps/side${side}_f${f}.log" | tail -3
    done
  done
fi

if want callgrind; then
  log "1c. callgrind: instructions and flops per bond"
  mkdir -p "$out/callgrind"
  for f in "${factors[@]}"; do
    d="$out/callgrind/f$f"
    mkdir -p "$d"
    valgrind --tool=callgrind --collect-atstart=no --dump-instr=yes --callgrind-out-file="$d/cg.out" \
      "$bench/kernel_profile" --side 100 --factor "$f" --callgrind >"$d/run.txt" 2>"$d/valgrind.txt"
    evaluated=$(sed -n 's/.* evaluated=\([0-9]*\).*/\1/p' "$d/run.txt")
    calls=$(sed -n 's/.* model_calls=\([0-9]*\).*/\1/p' "$d/run.txt")
    # regions in the order kernel_bench dumps them
    k=1
    for region in gent_warm assemble identity model_warm gent_cold gent_dynamics energy_warm; do
      count=$evaluated; [ "$region" = model_warm ] && count=$calls
      "$PY" "$here/bench/callgrind_flops.py" "$bench/kernel_profile" "$d/cg.out.$k" "$count" --label "$region" --json \
        >"$d/$region.json"
      "$PY" "$here/bench/callgrind_flops.py" "$bench/kernel_profile" "$d/cg.out.$k" "$count" --label "$region" --brief
      k=$((k + 1))
    done
  done
  if ((!quick)); then
    # Inside the solver: residual evaluations (one cbrt each) per model call during the
    # time steps: call counts of a 100-step run minus those of a 0-step run (the setup's
    # power iteration), default scene.
    for steps in 100 0; do
      d="$out/callgrind/solver"; ((steps == 0)) && d="$out/callgrind/solver0"
      mkdir -p "$d"
      valgrind --tool=callgrind --callgrind-out-file="$d/cg.out" \
        "$bapd" -options_file_yaml "$here/examples/default.yaml" -output_dir "$d/o" -end_step "$steps" \
        >"$d/run.txt" 2>"$d/valgrind.txt"
      "$PY" "$here/bench/callgrind_calls.py" "$d/cg.out" >"$d/calls.json"
      cat "$d/calls.json"
    done
  fi
fi

run_bapd() { # label ranks args...
  local label="$1" n="$2"
  shift 2
  "$PY" "$here/bench/bapd_run.py" --keep-best --exe "$bapd" --ranks "$n" --out "$out/runs" --label "$label" -- "$@" || true
}

if want scaling; then
  log "2 + 4a. memory per point and strong scaling (plate with a hole, delta = 3.015 dx)"
  # -body_dx for 1e5 and 1e6 points on the 80 x 160 mm plate with its 20 mm hole
  if ((quick)); then sizes=("1e5:3.5334e-4:60"); else sizes=("1e5:3.5334e-4:100" "1e6:1.1174e-4:20"); fi
  for s in "${sizes[@]}"; do
    IFS=: read -r name dx steps <<<"$s"
    for n in 1 "$ranks"; do
      run_bapd "scaling_${name}_np$n" "$n" "$here/examples/default.yaml" -body_dx "$dx" -end_step "$steps" \
        -output_interval 100000 -progress_interval 100000 -output_dir "$out/runs/o_scaling_${name}_np$n" -log_view
    done
  done
  # What the every-step "last good state" copy (-checkpoint_on_error) costs in memory.
  run_bapd "memory_1e5_np1_no_good_state" 1 "$here/examples/default.yaml" -body_dx 3.5334e-4 -end_step 10 \
    -checkpoint_on_error false -output_interval 100000 -progress_interval 100000 -output_dir "$out/runs/o_memory_ng"
fi

if want scenes; then
  log "3. time to solution of the paper scenes (0 and N steps, extrapolated)"
  if ((quick)); then nsteps=100; else nsteps=400; fi
  for scene in plate_hole pure_shear notched_pure_shear; do
    for n in 1 "$ranks"; do
      for steps in 0 "$nsteps"; do
        run_bapd "scene_${scene}_np${n}_s$steps" "$n" "$here/examples/$scene.yaml" -end_step "$steps" \
          -output_dir "$out/runs/o_${scene}_np${n}_s$steps" -progress_interval 100000 -log_view
      done
    done
  done
fi

if want partition; then
  log "4b. partition only: edge cut and ghosts for 2..1024 parts"
  mkdir -p "$out/partition"
  if ((quick)); then
    "$bench/partition_stats" --points 1e6 --parts 2,4,16,64 | tee "$out/partition/p1e6.txt"
  else
    "$bench/partition_stats" --points 1e6 | tee "$out/partition/p1e6.txt"
    "$bench/partition_stats" --points 1e7 | tee "$out/partition/p1e7.txt"
  fi
fi

if want accuracy; then
  log "5. plate with a hole: error against FEA vs wall time"
  if ((quick)); then
    cases=("0.004:3.015" "0.002:3.015")
  else
    cases=("0.004:2.515" "0.004:3.015" "0.004:3.515" "0.002:2.515" "0.002:3.015" "0.002:3.515" "0.001:2.515" "0.001:3.015"
           "0.001:3.515" "0.0005:2.515" "0.0005:3.015")
  fi
  # The fastest route to the same static states (examples/plate_hole_fast.yaml: fast
  # ramps, adaptive dynamic relaxation; docs/validation.md checks it against the slow one).
  for c in "${cases[@]}"; do
    IFS=: read -r dx f <<<"$c"
    run_bapd "accuracy_dx${dx}_f${f}" "$accuracy_ranks" "$here/examples/plate_hole.yaml" -body_dx "$dx" -horizon_factor "$f" \
      -options_file_yaml "$here/examples/plate_hole_fast.yaml" \
      -output_dir "$out/runs/o_accuracy_dx${dx}_f${f}" -progress_interval 100000
  done
fi

log "report"
"$PY" "$here/bench/report.py" "$out"
echo "results: $out"
