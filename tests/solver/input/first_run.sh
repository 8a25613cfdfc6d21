#!/usr/bin/env bash
# What a new user meets first. `bapd -version` (and bapd-fit's, and through mpiexec on
# 2 ranks and run_mpi.sh) prints the project's version (CMakeLists.txt) once, PETSc's and
# the MPI library, and exits 0; a run's first line names the same version. run_mpi.sh
# given options but no scene runs the default scene under them and says so in one line.
#   first_run.sh        (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
set -uo pipefail
src="$BAPD_SOURCE_DIR"
run_mpi="$src/run_mpi.sh"
fit="$(dirname "$BAPD_EXE")/bapd-fit"
work="input_first_run"
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }

version=$(sed -n 's/^project(bapd VERSION \([0-9.]*\).*/\1/p' "$src/CMakeLists.txt")
[ -n "$version" ] || fail "no project(bapd VERSION ...) in CMakeLists.txt"
# "0.3.0", then " (git DESCRIBE)" when built from a git checkout.
pattern="^bapd ${version//./\\.}( \(git [0-9A-Za-z._-]+\))?$"

timeout 60 "$BAPD_EXE" -version > serial.txt 2>&1 || fail "bapd -version: exit code $?"
grep -qE "$pattern" serial.txt || fail "bapd -version does not print 'bapd $version' on its first line"
grep -qE "^PETSc 3\.[0-9]+\.[0-9]+" serial.txt || fail "bapd -version does not print PETSc's version"
grep -qE "^MPI: .*[0-9]" serial.txt || fail "bapd -version does not print the MPI library"
(($(wc -l < serial.txt) == 3)) || fail "bapd -version prints $(wc -l < serial.txt) lines, not 3"

timeout 60 mpiexec -q -n 2 --oversubscribe "$BAPD_EXE" --version > np2.txt 2>&1 || fail "mpiexec -n 2 bapd --version: exit code $?"
cmp -s serial.txt np2.txt || fail "bapd --version on 2 ranks prints something else than -version on one (once)"
timeout 60 "$run_mpi" -n 2 -version > run_mpi.txt 2>&1 || fail "run_mpi.sh -version: exit code $?"
cmp -s serial.txt run_mpi.txt || fail "run_mpi.sh -version prints something else than bapd -version"

timeout 60 "$fit" -version > fit.txt 2>&1 || fail "bapd-fit -version: exit code $?"
grep -qE "^bapd-fit ${version//./\\.}( \(git [0-9A-Za-z._-]+\))?$" fit.txt || fail "bapd-fit -version does not print 'bapd-fit $version'"

# Options but no scene: the default scene under them (a few steps of it).
timeout 120 "$run_mpi" -n 1 -output_dir out -end_step 5 > default.txt 2>&1 || fail "run_mpi.sh -output_dir out -end_step 5: exit code $?"
notices=$(grep -c "^run_mpi.sh: no scene given: running the default scene examples/default.yaml" default.txt)
((notices == 1)) || fail "run_mpi.sh with options but no scene printed $notices notice line(s), not 1"
sed -n 2p default.txt | grep -qE "^bapd ${version//./\\.}.*, PETSc 3\.[0-9]+\.[0-9]+, .*, 1 rank\(s\)$" ||
  fail "the run's first line does not name bapd $version, PETSc and the ranks"
grep -q "hole centre (0.04, 0.08) m, radius 0.01 m" default.txt || fail "the default scene (its hole) was not run"
[ -f out/history.csv ] || fail "the options on top of the default scene were not applied (no out/history.csv)"
grep -q "error:" default.txt && fail "the default scene under options printed an error"

if ((failures)); then
  for f in serial.txt np2.txt run_mpi.txt fit.txt default.txt; do echo "--- $f"; sed 's/^/    | /' "$f"; done
  exit 1
fi
echo "bapd -version: $(head -1 serial.txt); the default scene runs under options given alone"
