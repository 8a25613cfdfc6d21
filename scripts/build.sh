#!/usr/bin/env bash
# Configures (once) and builds bapd in build/ (or $BAPD_BUILD_DIR).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BAPD_BUILD_DIR:-$here/build}"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$build" -j "$(nproc)" >/dev/null 2>"$build/build-errors.log" || {
  cat "$build/build-errors.log" >&2; cmake --build "$build" -j1 >&2; exit 1; }
