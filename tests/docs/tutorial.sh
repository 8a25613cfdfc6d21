#!/usr/bin/env bash
# docs/tutorial.md runs as written: every command block marked <!-- tutorial-test -->
# (the line just before its ```sh fence) is run, in the page's order, in one scratch
# directory laid out like the repository (run_mpi.sh, examples/ and scripts/ linked
# in), against the built bapd (BAPD_EXE: run_mpi.sh then builds nothing). The test
# fails on the first block that fails, printing the block and the end of its output,
# if the page has fewer marked blocks than it had when this test was written (a
# marker lost in an edit would silently skip its commands), or if a file the page
# says the commands write is missing.
#
#   bash tests/docs/tutorial.sh [PAGE]      (BAPD_EXE and BAPD_SOURCE_DIR from ctest)
set -uo pipefail
src="${BAPD_SOURCE_DIR:?set BAPD_SOURCE_DIR to the repository (ctest sets it)}"
export BAPD_EXE="${BAPD_EXE:?set BAPD_EXE to the built bapd (ctest sets it)}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
page="${1:-$src/docs/tutorial.md}"
min_blocks=7 # the marked blocks of docs/tutorial.md
work="$(mktemp -d "${TMPDIR:-/tmp}/bapd_tutorial.XXXXXX")"
trap 'rm -rf "$work"' EXIT
ln -s "$src/run_mpi.sh" "$src/examples" "$src/scripts" "$work/"

# The marked blocks, one file each: block_1.sh, block_2.sh, ...
awk -v dir="$work" '
  /^<!-- tutorial-test -->$/ { marked = 1; next }
  marked && /^```sh$/ { n++; file = sprintf("%s/block_%d.sh", dir, n); inside = 1; marked = 0; next }
  inside && /^```$/ { inside = 0; close(file); next }
  inside { print > file; next }
  { marked = 0 }
' "$page"
blocks=$(find "$work" -maxdepth 1 -name 'block_*.sh' | wc -l)
if ((blocks < min_blocks)); then
  echo "tutorial.sh: $page has $blocks marked command block(s), expected at least $min_blocks" \
       "(a <!-- tutorial-test --> line must come right before its \`\`\`sh fence)" >&2
  exit 1
fi

start=$SECONDS
for ((k = 1; k <= blocks; k++)); do
  block="$work/block_$k.sh"
  t0=$SECONDS
  if ! (cd "$work" && timeout 600 bash -eo pipefail "$block") > "$work/block_$k.log" 2>&1; then
    echo "tutorial.sh: block $k of $page failed:" >&2
    sed 's/^/    /' "$block" >&2
    echo "  its output (last 30 lines):" >&2
    tail -n 30 "$work/block_$k.log" | sed 's/^/    /' >&2
    exit 1
  fi
  echo "block $k: $((SECONDS - t0)) s ($(head -n 1 "$block"))"
done

# What the page says the commands write.
missing=0
for f in output/default/history.csv output/default/top_nominal_stress_Pa_vs_stretch.png \
         output/default/kinetic_energy_J_vs_time_s.png output/default/fields.xdmf \
         output/default/ux.png output/my_sheet/history.csv output/my_sheet_fine/history.csv \
         dx.png output/my_sheet_parts/checkpoint.h5; do
  [ -s "$work/$f" ] || { echo "tutorial.sh: the tutorial's commands did not write $f" >&2; missing=1; }
done
((missing == 0)) || exit 1
echo "tutorial.sh: $blocks blocks of $page ran in $((SECONDS - start)) s"
