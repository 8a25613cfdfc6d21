#!/usr/bin/env bash
# -help that helps (help.hpp): `bapd -help`, -h and --help list bapd's options alone,
# with units, values and "required"; every option of the tables of docs/options.md and
# docs/options_run.md is in it; `-help all` adds PETSc's. Through run_mpi.sh on RANKS ranks (printed once).
#   help.sh RANKS        (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
set -uo pipefail
ranks="$1"
src="$BAPD_SOURCE_DIR"
run_mpi="$src/run_mpi.sh"
work="input_help_np$ranks"
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }

for flag in -help -h --help; do
  timeout 60 "$run_mpi" -n "$ranks" "$flag" > "help$flag.txt" 2>&1 || fail "$flag: exit code $?"
done
cmp -s help-help.txt help-h.txt || fail "-h prints something else than -help"
cmp -s help-help.txt help--help.txt || fail "--help prints something else than -help"
h=help-help.txt
lines=$(wc -l < "$h")
((lines < 150)) || fail "-help prints $lines lines (bapd's options alone fit in 150)"
grep -q -- "-body_width <required> .*Sheet width along x \[m\]" "$h" || fail "-body_width is not shown as required with its unit"
grep -q -- "-horizon_factor <3.015>" "$h" || fail "-horizon_factor does not show its default 3.015"
grep -q "<0\. : 0\.>" "$h" && fail "PETSc's '<0. : 0.>' is still shown"
grep -q "(docs/options.md)" "$h" && fail "the manual-page suffix is still on every line"
for petsc in -options_monitor -ts_type -snes_monitor -device_enable "PetscOptionsGetViewer"; do
  grep -q -- "$petsc" "$h" && fail "-help lists PETSc's $petsc"
done
grep -q "error:" "$h" && fail "-help printed an error"
# Every option documented in docs/options.md and docs/options_run.md (the per-set and
# per-probe patterns aside).
missing=""
for opt in $(grep -hoE '^\| `-[a-z_]+`' "$src/docs/options.md" "$src/docs/options_run.md" | grep -oE -- '-[a-z_]+' | grep -v "NAME\|_S_\|_P_" | sort -u); do
  grep -q -- "^  $opt <" "$h" || missing+=" $opt"
done
[ -z "$missing" ] || fail "documented options missing from -help:$missing"
# One copy on every rank count.
count=$(grep -c -- "-body_width <" "$h")
((count == 1)) || fail "-body_width listed $count times"

# With a scene: its values, and the options of its load sets and probes.
timeout 60 "$run_mpi" -n "$ranks" "$src/examples/pure_shear.yaml" -help > scene.txt 2>&1 || fail "scene -help: exit code $?"
grep -q -- "-body_width <0.07>" scene.txt || fail "-help with a scene does not show the scene's width 0.07"
grep -q -- "-load_top_region <top>" scene.txt || fail "-help with a scene does not list -load_top_region"
grep -q "^Body: [0-9]" scene.txt && fail "-help built the body"

# -help all: PETSc's options too.
timeout 60 "$run_mpi" -n "$ranks" -help all > all.txt 2>&1 || fail "-help all: exit code $?"
grep -q -- "-ts_type" all.txt || fail "-help all does not list -ts_type"
grep -q -- "-body_width" all.txt || fail "-help all does not list -body_width"

if ((failures)); then
  echo "$failures check(s) failed; -help printed:"
  sed 's/^/    | /' "$h"
  exit 1
fi
echo "-help: $lines lines, every documented option, PETSc's only with -help all ($ranks rank(s))"
