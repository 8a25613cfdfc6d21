#!/usr/bin/env bash
# The dogbone of examples/dogbone.yaml on two discretisations of one Gmsh shape, for
# docs/discretisations.md "Lattice and element centroids": the uniform lattice (dx 0.5 mm)
# clipped to the mesh, and one point per element of the mesh (-body_outline_
# discretisation centroids), meshed at 1 mm (the .geo's own size) and at 0.75 mm (about
# the lattice's point count). Static state at stretch 1.5 by the fast route; grips are
# the 2 mm tab ends as boxes (the example's 4 rows), so both hold the same region.
# Force: bond-only with the tensor correction; the centroid clouds run with each affine
# patch correction (the *_off, *_on and *_virial cases: -force_patch_correction off, on
# = lambda, virial = lambda's patch test keeping the virial; auto is virial for given
# points), docs/discretisations.md. Prints, per case, the probe's ux, uy (mm) and the
# nominal stress s = top reaction / (20 mm x 2 mm) (kPa) at the end (stretch 1.5).
#   scripts/geometry/dogbone_discretisations.sh [OUT_DIR]     (from the repository root)
set -euo pipefail
out="${1:-/tmp/dogbone_discretisations}"
exe="${BAPD_EXE:-build/bapd}"
mkdir -p "$out"
sed 's/Mesh.CharacteristicLengthMax = 0.001;/Mesh.CharacteristicLengthMax = 0.00075;/' examples/geometry/dogbone.geo > "$out/dogbone_075.geo"
write_scene() { # write_scene FILE BODY_LINES
  cat > "$1" <<YAML
body:
$2
  width: 0.020
  height: 0.060
  thickness: 0.002
force_form: bond_only
material: {model: gent, mu: 4.55e3, Jm: 162.6, bulk_ratio: 1000, density: 1000}
load:
  sets: [top, bottom]
  top: {region: box, box: [0, 0.058, 0.02, 0.06], x: fixed, y: stretch}
  bottom: {region: box, box: [0, 0, 0.02, 0.002], x: fixed, y: fixed}
  schedule: [0, 1.0, 0.05, 1.5, 1.05, 1.5]
probes: [gauge_edge]
probe: {gauge_edge: {at: [0.00525, 0.030]}}
relaxation: adaptive
static_tolerance: 1e-10
damping: 200
output: {interval: 20}
progress_interval: 100000
YAML
}
write_scene "$out/lattice.yaml" "  dx: 0.0005
  shapes: [outline]
  outline: {type: mesh, op: intersect, file: examples/geometry/dogbone.geo}"
write_scene "$out/centroids_1mm.yaml" "  shapes: [outline]
  outline: {type: mesh, op: intersect, file: examples/geometry/dogbone.geo, discretisation: centroids}"
write_scene "$out/centroids_075mm.yaml" "  shapes: [outline]
  outline: {type: mesh, op: intersect, file: $out/dogbone_075.geo, discretisation: centroids}"
for case in lattice centroids_1mm_off centroids_1mm_on centroids_1mm_virial \
            centroids_075mm_off centroids_075mm_on centroids_075mm_virial; do
  echo "== $case"
  scene="${case%_*}" extra=()
  [ "$case" = lattice ] && scene=lattice || extra=(-force_patch_correction "${case##*_}")
  nice -n 5 mpiexec -n 1 "$exe" -options_file_yaml "$out/$scene.yaml" "${extra[@]}" -output_dir "$out/$case" > "$out/$case.log" 2>&1
  grep -E "^Body:|^Probe|^Patch|^  \(solved|^Finished|probe gauge|load set top|time step:" "$out/$case.log"
  /usr/bin/python3 - "$out/$case/history.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
last = rows[-1]
ux = [k for k in last if k.startswith("gauge_edge") and k.endswith("ux_m")]
uy = [k for k in last if k.startswith("gauge_edge") and k.endswith("uy_m")]
print(f"  end: ux {1e3 * float(last[ux[0]]):.4f} mm, uy {1e3 * float(last[uy[0]]):.3f} mm, "
      f"s {float(last['top_reaction_y_N']) / (0.020 * 0.002) / 1e3:.4f} kPa")
PY
done
