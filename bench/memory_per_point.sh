#!/usr/bin/env bash
# Memory per point of bapd, one or two executables side by side (docs/performance.md
# section 2): the plate with a hole (examples/default.yaml, delta = 3.015 dx, the features
# on: -checkpoint_on_error is the default) at ~1e5 and ~4e5 points, 10 steps, one rank.
# Peak RSS (VmHWM, bench/bapd_run.py) per point at each size, and the marginal bytes per
# point between the two sizes, which leaves out the fixed ~48 MB of MPI/PETSc libraries
# that a 1e5-point figure carries (the 1e6-point figure of section 2 is near the marginal).
#
#   bench/memory_per_point.sh BAPD [BAPD_OTHER] [--out DIR] [-- extra bapd options]
#
# RSS does not depend on the machine's load, so the two executables need not alternate.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
exes=()
out="/tmp/bapd-memory-$(date +%Y%m%d-%H%M%S)"
extra=()
while (($#)); do
  case "$1" in
    --out) out="$2"; shift 2 ;;
    --) shift; extra=("$@"); break ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    *) exes+=("$1"); shift ;;
  esac
done
((${#exes[@]} >= 1)) || { echo "memory_per_point.sh: give at least one bapd executable (see --help)" >&2; exit 2; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mkdir -p "$out"
sizes=("1e5:3.5334e-4" "4e5:1.7667e-4") # -body_dx on the 80 x 160 mm plate with its 20 mm hole
for e in "${!exes[@]}"; do
  for s in "${sizes[@]}"; do
    IFS=: read -r name dx <<<"$s"
    /usr/bin/python3 "$here/bench/bapd_run.py" --exe "${exes[$e]}" --ranks 1 --out "$out" --label "exe${e}_$name" -- \
      "$here/examples/default.yaml" -body_dx "$dx" -end_step 10 -output_interval 100000 -progress_interval 100000 \
      -output_dir "$out/o_exe${e}_$name" "${extra[@]}" >/dev/null
  done
done
/usr/bin/python3 - "$out" "${exes[@]}" <<'EOF'
import json, sys
out, exes = sys.argv[1], sys.argv[2:]
print(f"{'executable':<40} {'points':>9} {'peak MB':>8} {'B/point':>8}   marginal B/point (1e5 -> 4e5)")
for e, exe in enumerate(exes):
    r = [json.load(open(f"{out}/exe{e}_{n}.json")) for n in ("1e5", "4e5")]
    per = [x["peak_rss_mb"] * 2**20 / x["points"] for x in r]
    marginal = (r[1]["peak_rss_mb"] - r[0]["peak_rss_mb"]) * 2**20 / (r[1]["points"] - r[0]["points"])
    for x, p in zip(r, per):
        print(f"{exe[-40:]:<40} {x['points']:>9} {x['peak_rss_mb']:>8.1f} {p:>8.0f}")
    print(f"{'':<40} {'':>9} {'':>8} {'':>8}   {marginal:.0f}")
EOF
