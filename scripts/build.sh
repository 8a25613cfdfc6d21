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
# (warnings, errors) as it comes, line by line (a shell loop: awk would read ahead).
progress() {
  local line step path
  while IFS= read -r line; do
    if [[ "$line" =~ ^(\[[^]]*\])\ Building\ (C|CXX)\ object\ ([^ ]+) ]]; then
      step="${BASH_REMATCH[1]}" path="${BASH_REMATCH[3]}"
      local target="${path%%.dir/*}"
      target="${target##*/}"
      path="${path#*.dir/}"
      echo "$step $target: ${path%.o}"
    elif [[ "$line" =~ ^(\[[^]]*\])\ Linking\ (C|CXX)\ [a-z\ ]+\ ([^ ]+) ]]; then
      echo "${BASH_REMATCH[1]} linking ${BASH_REMATCH[3]##*/}"
    elif [[ "$line" =~ ^\[[^]]*\]\ Built\ target || "$line" =~ Consolidate\ compiler\ generated\ dependencies ||
      "$line" =~ ^--\ (Configuring\ done|Generating\ done|Build\ files\ have\ been\ written) ]]; then
      :
    else
      echo "$line"
    fi
  done
}
set +e
cmake --build "$build" -j "$jobs" "${targets[@]}" 2>&1 | tee "$build/build.log" | progress
status=${PIPESTATUS[0]}
set -e
if ((status != 0)); then
  echo "build.sh: error: the build failed (the compiler's messages are above, and in $build/build.log)" >&2
  exit "$status"
fi
echo "build.sh: built $what in $build"
