#!/usr/bin/env bash
# The fault sweep (docs/faults.md): a few hundred short runs of bapd, each given one
# fault (a mutated option or file, a signal, a full disk), each classified: clean,
# crash, hang, silent or data loss. Prints a table and a summary; exits non-zero if a
# case is not clean.
#   scripts/faults/sweep.sh [--cases N] [--seed S] [--only KIND,...] [--work DIR] [--smoke]
# BAPD_EXE (default build/bapd) is the program run; run_mpi.sh launches it.
exec /usr/bin/python3 "$(dirname "${BASH_SOURCE[0]}")/sweep.py" "$@"
