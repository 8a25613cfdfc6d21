#!/usr/bin/env bash
# The same scene on 1, 2, 3 and 4 ranks: the same history, final displacement field
# (bit for bit: tolerance 0) and set of broken bonds.
#   rank_invariance.sh elastic|fracture|fracture_energy|fracture_corrected|fracture_incompressible|shapes|waisted_sheet|dogbone|double_edge_notched|cloud|volumetric_point
# (dogbone, double_edge_notched: the examples from Gmsh files, gripped by physical group,
# pulled a little; on 1, 2 and 3 ranks)
# (fracture_corrected: fracture with the bond-only form and -force_stress_correction tensor, whose per-point
# correction is built once from the unbroken families on every rank, ghosts included)
# (volumetric_point: elastic in plane strain at K = 1000 mu with -material_volumetric point, whose
# per-point mean dilatation is formed from the point's own bonds on every rank)
# (fracture_incompressible: fracture in -material_formulation plane_stress_incompressible,
# C33 = 1/J~^2 per bond, no solve and no warm start; on 1, 2 and 3 ranks)
# (fracture_energy: fracture by -failure_fracture_energy, whose pair energies need both
# directed copies of a bond: a ring-1 ghost's from its own family on this rank)
set -euo pipefail
case="$1"
work="rank_invariance_$case"
rm -rf "$work"; mkdir -p "$work"
# A notched sheet pulled apart: plane-stress Gent, coarse enough to run in seconds.
scene=(-body_width 0.03 -body_height 0.012 -body_thickness 0.003 -body_dx 0.0005
       -body_notches 0.02,0.006,0.03,0.006 -horizon_factor 3.015
       -material_mu 4.55e3 -material_Jm 162.6 -material_bulk_ratio 100 -material_density 1000
       -load_sets top,bottom -load_top_region top -load_top_x fixed -load_top_y stretch -load_top_y_scale 1
       -load_bottom_region bottom -load_bottom_x fixed -load_bottom_y fixed
       -probes mouth -probe_mouth_at 0.03,0.0062 -damping 40 -output_interval 50 -progress_interval 100000
       -output_final_state)
if [ "$case" = shapes ]; then
  # A waisted sheet with an elliptical pore and a polygonal window (shape.hpp): the
  # lattice the shapes leave, partitioned 1 to 4 ways.
  scene=(-body_width 0.02 -body_height 0.03 -body_thickness 0.002 -body_dx 0.0005 -horizon_factor 3.015
         -body_shapes left,right,pore,window
         -body_left_type circle -body_left_centre -0.008,0.015 -body_left_radius 0.012
         -body_right_type circle -body_right_centre 0.028,0.015 -body_right_radius 0.012
         -body_pore_type ellipse -body_pore_centre 0.01,0.015 -body_pore_radii 0.0015,0.0008 -body_pore_angle 30
         -body_window_type polygon -body_window_points 0.010,0.022,0.013,0.025,0.010,0.028,0.007,0.025
         -material_mu 4.55e3 -material_Jm 162.6 -material_bulk_ratio 100 -material_density 1000
         -load_sets top,bottom -load_top_region top -load_top_layers 2 -load_top_x fixed -load_top_y stretch
         -load_bottom_region bottom -load_bottom_layers 2 -load_bottom_x fixed -load_bottom_y fixed
         -probes waist -probe_waist_at 0.00425,0.015 -damping 40 -output_interval 50 -progress_interval 100000
         -output_final_state -load_schedule 0,1,0.05,1.2)
elif [ "$case" = waisted_sheet ]; then
  # The example as shipped (examples/waisted_sheet.yaml: scene shapes only, discs that
  # reach outside the sides, an ellipse and a polygon cut out), a short pull.
  scene=(-options_file_yaml "$BAPD_SOURCE_DIR/examples/waisted_sheet.yaml"
         -load_schedule 0,1,0.02,1.05 -output_interval 20 -progress_interval 100000 -output_final_state)
elif [ "$case" = dogbone ] || [ "$case" = double_edge_notched ]; then
  # The example as shipped, its Gmsh file found from the source tree, a short pull.
  scene=(-options_file_yaml "$BAPD_SOURCE_DIR/examples/$case.yaml"
         -body_outline_file "$BAPD_SOURCE_DIR/examples/geometry/$case.geo"
         -load_schedule 0,1,0.02,1.05 -output_interval 20 -progress_interval 100000 -output_final_state)
elif [ "$case" = cloud ]; then
  # The graded point cloud of examples/point_cloud.yaml (own volumes and horizons, a hole
  # cut by the scene, the bond-only form with the tensor correction and the affine patch
  # correction (auto: virial, 5 numbers a point shipped with the points), stretched briefly.
  scene=(-options_file_yaml "$BAPD_SOURCE_DIR/examples/point_cloud.yaml"
         -body_cloud "$BAPD_SOURCE_DIR/examples/geometry/graded_sheet.csv"
         -force_form bond_only -load_schedule 0,1,0.05,1.2 -output_interval 50 -progress_interval 100000 -output_final_state)
elif [ "$case" = fracture ] || [ "$case" = fracture_corrected ] || [ "$case" = fracture_incompressible ]; then
  # Stretch the sheet fast enough that the notch opens and bonds break within the run.
  # fracture: a notch to x = 17 mm; bonds break from step 280 and the crack runs from its
  # tip along y = 6 mm, where 3 and 4 ranks have a boundary; on 2 ranks the boundary is
  # at x = 15 mm, across the crack's path, which the crack has crossed by step 580 (24
  # bonds across it; none at step 520). (From a notch to x = 20 mm, as in the other
  # cases, the crack would reach it near step 650, and every step after the crack starts
  # costs the crack-tip search's force evaluations.) fracture_corrected: the corrected form
  # breaks its first bonds from step 347 (stretch 1.20), 14 by step 500, each between
  # points of two of the 3 ranks; the crack's later run adds force evaluations, not cases.
  # fracture_incompressible: bonds break from step 278; the crack crosses the 2 ranks'
  # boundary at x = 15 mm by step 650 (18 bonds join points of the two; none at step 600).
  scene+=(-load_schedule 0,1,0.15,1.45 -failure_critical_stretch 2.0)
  if [ "$case" = fracture_corrected ]; then
    scene+=(-force_form bond_only -force_stress_correction tensor -end_step 500)
  elif [ "$case" = fracture_incompressible ]; then
    scene+=(-material_formulation plane_stress_incompressible -end_step 650)
  else
    scene+=(-body_notches 0.017,0.006,0.03,0.006 -end_step 600)
  fi
elif [ "$case" = volumetric_point ]; then
  scene+=(-load_schedule 0,1,0.1,1.3 -material_formulation plane_strain -material_bulk_ratio 1000 -material_volumetric point
          -end_step 400)
elif [ "$case" = fracture_energy ]; then
  # Bonds break from step 466, 26 by step 550, 20 of them along the 3 ranks' boundary
  # (the crack crosses the sheet by step 1400, which adds nothing here).
  scene+=(-load_schedule 0,1,0.15,1.45 -failure_fracture_energy 6 -end_step 550)
else
  scene+=(-load_schedule 0,1,0.05,1.3)
fi
ranks=(1 2 3 4)
# The crack's cases on 1 and 3 ranks only (the elastic ones cover 2 and 4): a running
# crack costs five force evaluations a step for the crack-tip search.
case "$case" in dogbone|double_edge_notched|waisted_sheet|fracture_incompressible) ranks=(1 2 3) ;; fracture_corrected|fracture_energy) ranks=(1 3) ;; esac
# (The crack's cases write the fields at the start and the end: the owner of each point.)
case "$case" in fracture*) scene+=(-output_fields -output_fields_interval 100000) ;; esac
for n in "${ranks[@]}"; do
  mpiexec -n $n --oversubscribe --bind-to none "$BAPD_EXE" "${scene[@]}" -output_dir "$work/np$n" > "$work/np$n.log" 2>&1 ||
    { cat "$work/np$n.log"; exit 1; }
done
python3 "$BAPD_SOURCE_DIR/tests/mpi/compare_runs.py" --tolerance 0 $(case "$case" in fracture*) echo --expect-broken ;; esac) \
  $(for n in "${ranks[@]}"; do echo "$work/np$n"; done)
case "$case" in fracture*)
  # The point of the crack's cases: bonds between points of different ranks broke, on
  # every rank count (the owner of each point from the last field file, in natural order).
  for n in "${ranks[@]:1}"; do
    /usr/bin/python3 - "$work/np$n" $n << 'PY' || exit 1
import csv, glob, sys
import h5py
run, n = sys.argv[1], sys.argv[2]
with h5py.File(sorted(glob.glob(run + "/fields/step_*.h5"))[-1], "r") as f:
    owner = f["rank"][()]
with open(run + "/broken_bonds.csv") as f:  # each bond twice, (i, j) and (j, i)
    bonds = [(int(r["i"]), int(r["j"])) for r in csv.DictReader(f) if int(r["i"]) < int(r["j"])]
across = sum(owner[i] != owner[j] for i, j in bonds)
print(f"np{n}: {across} of {len(bonds)} broken bonds join points of two ranks")
sys.exit(0 if across > 0 else f"np{n}: no broken bond joins points of two ranks: the crack never met a rank boundary")
PY
  done ;;
esac
