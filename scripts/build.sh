#!/usr/bin/env bash
# Configures (once) and builds bapd in build/ (or $BAPD_BUILD_DIR), one line per file
# compiled; the compiler's messages are shown in full.
#
#   scripts/build.sh          everything: bapd, bapd-fit and the test suite
#   scripts/build.sh --run    bapd and bapd-fit alone (run_mpi.sh): about half the files,
#                             and a new build directory is configured without the tests,
#                             so GoogleTest need not be installed
#
# A full build switches the tests on in a build directory configured without them; --run
# leaves a directory configured with them as it is (and builds only its two programs).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BAPD_BUILD_DIR:-$here/build}"
mode=all
case "${1:-}" in
  "") ;;
  --run) mode=run ;;
  *) echo "build.sh: error: unknown argument '$1': give nothing (build everything) or --run (bapd and bapd-fit alone)" >&2; exit 2 ;;
esac

# configure OPTIONS...: cmake's own output is shown only if it fails.
configure() {
  mkdir -p "$build"
  if ! cmake -S "$here" -B "$build" "$@" > "$build/configure.log" 2>&1; then
    cat "$build/configure.log" >&2
    echo "build.sh: error: cmake could not configure $build (its output is above)" >&2
    exit 1
  fi
}
if [ ! -f "$build/CMakeCache.txt" ]; then
  tests=ON
  [ "$mode" = run ] && tests=OFF
  echo "build.sh: configuring $build (Release, tests $([ "$tests" = ON ] && echo on || echo off))"
  configure -DCMAKE_BUILD_TYPE=Release -DBAPD_BUILD_TESTS="$tests"
elif [ "$mode" = all ] && grep -q '^BAPD_BUILD_TESTS:BOOL=OFF' "$build/CMakeCache.txt"; then
  echo "build.sh: switching the tests on in $build"
  configure -DBAPD_BUILD_TESTS=ON
fi

targets=()
what="bapd, bapd-fit and the tests"
if [ "$mode" = run ]; then
  targets=(--target bapd bapd-fit)
  what="bapd and bapd-fit"
fi
jobs="$(nproc)"
echo "build.sh: building $what ($jobs jobs; the full log goes to $build/build.log)"
# Make's and Ninja's progress lines, shortened to the file or program; everything else
# (warnings, errors) as it comes. -Oline: the messages of one compiler run stay together with -j.
export MAKEFLAGS="${MAKEFLAGS:-} -Oline"
set +e
cmake --build "$build" -j "$jobs" "${targets[@]}" 2>&1 | tee "$build/build.log" | awk '
  /^\[ *[0-9]+(%|\/[0-9]+)\] / {
    match($0, /^\[[^]]*\]/); progress = substr($0, 1, RLENGTH)
    if (match($0, /Building (C|CXX) object [^ ]+/)) {
      file = substr($0, RSTART, RLENGTH); sub(/.* object /, "", file)
      target = file; sub(/\.dir\/.*/, "", target); sub(/.*\//, "", target)
      sub(/.*\.dir\//, "", file); sub(/\.o$/, "", file)
      print progress " " target ": " file; fflush(); next
    }
    if (match($0, /Linking (C|CXX) (executable|static library|shared library) [^ ]+/)) {
      program = substr($0, RSTART, RLENGTH); sub(/.* /, "", program)
      print progress " linking " program; fflush(); next
    }
    if ($0 ~ /Built target/) next
  }
  /Consolidate compiler generated dependencies/ { next }
  /^-- (Configuring done|Generating done|Build files have been written)/ { next }
  { print; fflush() }'
status=${PIPESTATUS[0]}
set -e
if ((status != 0)); then
  echo "build.sh: error: the build failed (the compiler's messages are above, and in $build/build.log)" >&2
  exit "$status"
fi
echo "build.sh: built $what in $build"
