#!/usr/bin/env bash
# Builds bapd if needed and runs it with MPI.
#
#   ./run_mpi.sh                                   # the default scene on 2 ranks
#   ./run_mpi.sh -n 4 examples/plate_hole.yaml     # a scene on 4 ranks
#   ./run_mpi.sh -n 2 examples/pure_shear.yaml -material_mu 5e3 -log_view
#   ./run_mpi.sh -output_dir out -end_step 100     # the default scene, with these options
#
# The first .yaml argument (or -options_file_yaml FILE) is the scene (passed as
# -options_file_yaml, first, so that every later option overrides it); every other
# argument goes to bapd unchanged. A scene that cannot be read, or a bad -n, is
# reported before anything is installed or built. The first run installs what running
# needs (scripts/install-deps.sh) and builds bapd and bapd-fit alone (scripts/build.sh
# --run); scripts/test.sh adds the test suite.
set -euo pipefail
# A stop before the run has started (a Ctrl-C while the checks below run): one line.
for sig in INT TERM HUP; do
  trap "echo 'bapd: error: interrupted by SIG$sig before the run had started: nothing was written; run it again to start over' >&2; exit 1" "$sig"
done
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ranks=2
scene=""
args=()
while (($#)); do
  case "$1" in
    -n|-np)
      if (($# < 2)) || ! [[ "$2" =~ ^[1-9][0-9]*$ ]]; then
        echo "run_mpi.sh: error: $1 needs a number of ranks, e.g. $1 4" >&2; exit 2
      fi
      ranks="$2"; shift 2 ;;
    -options_file_yaml)
      (($# >= 2)) || { echo "run_mpi.sh: error: -options_file_yaml needs a scene file, e.g. -options_file_yaml examples/pure_shear.yaml" >&2; exit 2; }
      if [ -z "$scene" ]; then scene="$2"; else args+=("$1" "$2"); fi; shift 2 ;;
    *.yaml|*.yml) if [ -z "$scene" ]; then scene="$1"; else args+=("$1"); fi; shift ;;
    *) args+=("$1"); shift ;;
  esac
done
# No scene named: the default scene, with any options on top of it; not when the options
# need no scene (-help, -version) or bring their own (-restart continues a checkpoint with
# its options; -options_file; -body_* options describe a body of their own, which the
# default scene's hole would otherwise be cut from).
if [ -z "$scene" ]; then
  own_scene=""
  for a in ${args[@]+"${args[@]}"}; do
    case "$a" in -help|-h|--help|-version|--version|-restart|-options_file|-body_*) own_scene="$a" ;; esac
  done
  if [ -z "$own_scene" ]; then
    scene="$here/examples/default.yaml"
    ((${#args[@]} == 0)) ||
      echo "run_mpi.sh: no scene given: running the default scene examples/default.yaml with the options on top (./run_mpi.sh SCENE.yaml [options] runs another)"
  fi
fi
if [ -n "$scene" ] && ! [ -f "$scene" -a -r "$scene" ]; then
  echo "bapd: error: cannot open scene file '$scene': $([ -e "$scene" ] && echo "not a readable file" || echo "No such file or directory") (check the path given to run_mpi.sh)" >&2
  exit 1
fi
if [ -z "${BAPD_EXE:-}" ]; then
  "$here/scripts/install-deps.sh"
  "$here/scripts/build.sh" --run
  BAPD_EXE="${BAPD_BUILD_DIR:-$here/build}/bapd"
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
scene_args=()
[ -n "$scene" ] && scene_args=(-options_file_yaml "$scene")
# -q: no Open MPI banner after a failed run; bapd's own message is the explanation.
# mpiexec runs as a child so that a rank killed by a signal (which bapd cannot report
# itself) still gets one line; the signals a user or a batch system sends to this
# script (SIGTERM, SIGINT: checkpoint and stop; SIGUSR1: checkpoint and go on) are
# passed on to mpiexec, which passes them on to the ranks. Open MPI 4's mpiexec
# passes SIGINT (and SIGHUP) on as SIGTERM, and kills the ranks 1 s after a SIGTERM; SIGUSR2 it
# passes on at once and leaves alone. So SIGINT, SIGTERM and SIGHUP go on as SIGUSR2 (bapd:
# checkpoint and stop), and the signal's real name goes to $BAPD_SIGNAL_FILE, which
# bapd reads for its message. mpiexec runs in a session of its own (setsid): a Ctrl-C
# in a terminal reaches this script only, not the ranks as well.
# What mpiexec needs before it starts a rank, checked here where its own failure would
# be a page of PMIx errors or a hang: a writable TMPDIR with room for its session files
# (a few MB of shared memory), and file descriptors for the ranks' pipes (the soft limit
# is raised to that when the hard one allows).
tmp="${TMPDIR:-/tmp}"
if ! [ -d "$tmp" ] || ! [ -w "$tmp" ] || ! [ -x "$tmp" ]; then
  echo "bapd: error: TMPDIR '$tmp' is not a writable directory, and mpiexec keeps its session files there: set TMPDIR to one (e.g. TMPDIR=/tmp ./run_mpi.sh ...)" >&2; exit 1
fi
tmp_free_kb=$(df -Pk "$tmp" 2> /dev/null | awk 'NR == 2 { print $4 }')
if [ -n "$tmp_free_kb" ] && ((tmp_free_kb < 4096)); then
  echo "bapd: error: TMPDIR '$tmp' has ${tmp_free_kb} kB free, and mpiexec needs a few MB there for its session files: free some space there or set TMPDIR to another directory" >&2; exit 1
fi
files_needed=$((32 + 4 * ranks))
if [ "$(ulimit -S -n)" != unlimited ] && (($(ulimit -S -n) < files_needed)); then
  ulimit -S -n "$files_needed" 2> /dev/null ||
    { echo "bapd: error: the limit on open files (ulimit -n $(ulimit -S -n), at most $(ulimit -H -n)) is too small for mpiexec and $ranks rank(s), which need about $files_needed: raise it (ulimit -n 1024) or run on fewer ranks" >&2; exit 1; }
fi
signal_file="$(mktemp "$tmp/bapd_signal.XXXXXX")"
trap 'rm -f "$signal_file"' EXIT
# A SIGKILL runs no trap: a watcher (its own session, so that a Ctrl-C to this script's
# group leaves it; no terminal or pipe held open) removes the file once this script is gone.
setsid bash -c 'tail --pid="$1" -f /dev/null; rm -f "$2"' bapd_signal_cleanup $$ "$signal_file" < /dev/null > /dev/null 2>&1 &
export BAPD_SIGNAL_FILE="$signal_file"
# mpiexec gets SIGTERM should this script die without passing a signal on (kill -9):
# it then stops the ranks, instead of running on without anyone waiting for it.
launch=(setsid)
command -v setpriv > /dev/null && launch+=(setpriv --pdeathsig TERM)
run=("${launch[@]}" mpiexec -q -x BAPD_SIGNAL_FILE -n "$ranks" --oversubscribe --bind-to none "$BAPD_EXE" "${scene_args[@]}" "${args[@]}")
if [ -p /dev/stdout ]; then
  # Output into a pipe whose reader may end first (| head): mpiexec would abort the ranks
  # with SIGTERM at its SIGPIPE. A relay takes the output instead; when the reader is
  # gone it asks this script for a stop as for SIGTERM, named SIGPIPE, and drains the rest.
  "${run[@]}" > >(cat || { kill -PIPE $$; exec cat > /dev/null; }) &
else
  "${run[@]}" &
fi
child=$!
for sig in TERM INT HUP PIPE; do trap "echo SIG$sig > '$signal_file'; kill -USR2 $child 2> /dev/null" "$sig"; done
trap "kill -USR1 $child 2> /dev/null" USR1
status=0
while :; do
  wait "$child" 2> /dev/null && status=0 || status=$? # (bash's own "User defined signal 2" line: reported below)
  kill -0 "$child" 2> /dev/null || break # a trapped signal ends wait early: wait again
done
if ((status == 128 + $(kill -l USR2))) && [ -s "$signal_file" ]; then
  # (this script's own SIGUSR2 reached mpiexec before it could pass it on)
  echo "bapd: error: interrupted by $(cat "$signal_file") before the run had started: nothing was written; run it again to start over" >&2
  status=1 # (as bapd's own interrupted exit)
elif ((status > 128)); then
  signal="$(kill -l $((status - 128)) 2> /dev/null || echo $((status - 128)))"
  echo "bapd: error: a bapd process was killed by SIG$signal (exit status $status) before it could report anything" \
       "(SIGKILL is how the out-of-memory killer and batch time limits stop a run): the output directory keeps what" \
       "was written before; continue from its checkpoint with -restart <output_dir>/checkpoint.h5 if one was written" >&2
fi
exit "$status"
