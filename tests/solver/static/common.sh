# Sourced by the static solver's test scripts (ctest sets BAPD_EXE and BAPD_SOURCE_DIR):
# strict mode, a fresh work directory, fail() and finish(), the plate with a hole's options.
#   . "$(dirname "$0")/common.sh" WORK_DIRECTORY
set -uo pipefail
src="$BAPD_SOURCE_DIR"
work="$1"
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }
# finish NAME: "NAME: passed" when nothing failed; the exit status.
finish() {
  ((failures == 0)) && echo "$1: passed"
  exit $((failures > 0))
}
# The plate with a hole (examples/plate_hole.yaml, the static solver's scene); a script adds its -body_dx.
plate=(-options_file_yaml "$src/examples/plate_hole.yaml" -progress_wall_interval 0)
