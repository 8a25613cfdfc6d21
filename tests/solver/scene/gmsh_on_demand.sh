#!/usr/bin/env bash
# Gmsh's library is opened on the first Gmsh read (src/solver/input/gmsh_library.cpp):
#   1. a scene without a Gmsh file runs without loading it (the dynamic loader's log
#      names no libgmsh), and a scene with one loads it and reads its outline;
#   2. with a broken libgmsh first on the library path, the scene without a Gmsh file
#      still runs to its end, and the scene with one stops with one error line that
#      names the library and the fix, a non-zero exit and no crash.
#   gmsh_on_demand.sh   (ctest sets BAPD_EXE and BAPD_SOURCE_DIR)
set -uo pipefail
src="$BAPD_SOURCE_DIR"
work="scene_gmsh_on_demand"
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
failures=0
fail() { echo "FAIL $1"; [ -f "${2:-}" ] && tail -n 5 "$2" | sed 's/^/    | /'; failures=$((failures + 1)); }
# bapd alone, an MPI singleton (as bad_input.sh runs it on 1 rank)
bapd() { timeout 120 env OMPI_MCA_ess_singleton_isolated=1 "$BAPD_EXE" "$@"; }
plain=(-options_file_yaml "$src/tests/data/scenes/tiny.yaml" -end_step 2)
outline=(-options_file_yaml "$src/tests/data/scenes/tiny.yaml" -end_step 2 -body_shapes cut -body_cut_type mesh
         -body_cut_op intersect -body_cut_file "$src/examples/geometry/double_edge_notched.geo")

LD_DEBUG=files bapd "${plain[@]}" -output_dir plain > plain.log 2> plain.loader.log || fail "the scene without a Gmsh file: exit $?" plain.log
grep -q "file=libgmsh" plain.loader.log && fail "the scene without a Gmsh file loaded libgmsh" plain.loader.log
LD_DEBUG=files bapd "${outline[@]}" -output_dir outline > outline.log 2> outline.loader.log ||
  fail "the scene with a Gmsh outline: exit $?" outline.log
grep -q "file=libgmsh" outline.loader.log || fail "the scene with a Gmsh outline did not load libgmsh" outline.loader.log
grep -q "shape cut: intersect a mesh" outline.log || fail "the outline was not read" outline.log

# A library that is no ELF file, found first (dlopen searches LD_LIBRARY_PATH first),
# under the name bapd opens (its SONAME, which bapd holds as a string).
name=$(grep -aom1 'libgmsh\.so[.0-9]*' "$BAPD_EXE") || { echo "FAIL no libgmsh name in $BAPD_EXE"; exit 1; }
mkdir -p broken && echo "not a library" > "broken/$name"
LD_LIBRARY_PATH="$PWD/broken${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" bapd "${plain[@]}" -output_dir plain_broken > plain_broken.log 2>&1 ||
  fail "the scene without a Gmsh file needed the broken libgmsh: exit $?" plain_broken.log
LD_LIBRARY_PATH="$PWD/broken${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" bapd "${outline[@]}" -output_dir outline_broken > outline_broken.log 2>&1
rc=$?
if ((rc == 0 || rc >= 124)); then fail "the scene with a Gmsh outline and a broken libgmsh: exit $rc (want a clean non-zero exit)" outline_broken.log; fi
[ "$(grep -c "error:" outline_broken.log)" = 1 ] || fail "want exactly one error line" outline_broken.log
grep "bapd: error:" outline_broken.log | grep -qF -- "-body_cut_file: Gmsh cannot read" || fail "the error names no option" outline_broken.log
grep "bapd: error:" outline_broken.log | grep -qF "$name cannot be loaded" || fail "the error names no library" outline_broken.log
grep "bapd: error:" outline_broken.log | grep -qF "install Gmsh" || fail "the error gives no fix" outline_broken.log
grep -qiE "PETSC ERROR|Segmentation|core dumped|terminate called" outline_broken.log && fail "a stack or a crash" outline_broken.log

if ((failures)); then
  echo "$failures check(s) failed"
  exit 1
fi
echo "libgmsh loaded only for a Gmsh file; a broken one named in one error line, and not needed without a Gmsh file"
