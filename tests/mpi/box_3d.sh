#!/usr/bin/env bash
# The 3D driver on a small box, 10 x 6 x 4 cells of 1 mm (240
# points, compressible Gent, K = 10 mu so that a few hundred steps pull it visibly),
# held on x- and pulled on x+, with tolerance 0 throughout:
#   box_3d.sh rank_invariance  1, 2, 3 and 4 ranks (4 oversubscribed on a 2-core
#                              machine): the same history.csv (with its
#                              z columns) and final displacements
#   box_3d.sh failure          a low critical stretch: bonds break, identically on 1
#                              and 2 ranks (the broken pairs too); then a low fracture
#                              energy, identically on 1 and 3 ranks
#   box_3d.sh restart          stopped at step N with a checkpoint and continued with
#                              -restart on 2 and on 3 ranks: the uninterrupted run's
#                              history, displacements and last field file
#   box_3d.sh ogden            the Ogden law in 3D (its own model, Ogden3D: eigenvalues
#                              of C a bond) with one term, alpha = 2, mu_1 = mu, is the
#                              compressible neo-Hookean law: the same run to 1e-10 (1 rank
#                              against 2, one fixed step; measured 2.3e-12: round-off of
#                              the eigen-decomposition); the default two-term Ogden must
#                              differ from it (its reaction by 1.2e-3; > 1e-4 asserted)
#   box_3d.sh graded_cloud     a 3D cloud of two spacings (a coarse block, 2 mm, beside a
#                              fine one, 1 mm): each point its own horizon, delta_i =
#                              3.015 cbrt(V_i), a bond where either reaches: the run's
#                              bond count must be the rule's, counted here pair by pair
#                              (13 860; the one horizon 3.015 mm gave 11 864), and
#                              1 and 2 ranks the same history and displacements; the
#                              blocks 4 mm apart (bridged by the coarse horizon only)
#                              run, 10 mm apart are refused as two pieces
#   box_3d.sh patch_cloud      a jittered 3D cloud (1200 points, volumes +-20 %), bond-only
#                              with -force_patch_correction virial: the setup solve reports
#                              its interior, iterations and residual, 1 and 2 ranks the same
#                              history and displacements; auto picks virial; off differs
set -euo pipefail
source "$BAPD_SOURCE_DIR/tests/mpi/restart/common.sh" # run, checkpointed_runs, fail, history_column, PYTHON
case="$1"
work="box_3d_$case"
rm -rf "$work"; mkdir -p "$work"
BOX=(-body_dimension 3 -body_dx 0.001 -body_shapes block -body_block_type box -body_block_box 0,0,0,0.010,0.006,0.004
     -horizon_factor 3.015 -material_mu 4.55e3 -material_Jm 162.6 -material_bulk_ratio 10 -material_density 1000
     -load_sets left,right -load_left_region x- -load_left_x fixed -load_left_y fixed -load_left_z fixed
     -load_right_region x+ -load_right_x stretch -load_right_y fixed -load_right_z fixed -load_reference_length 0.010
     -probes p -probe_p_at 0.0085,0.0035,0.0025 -damping 40 -output_interval 20 -progress_interval 100000 -output_final_state)
compare() { python3 "$BAPD_SOURCE_DIR/tests/mpi/compare_runs.py" --tolerance 0 "$@"; }
if [ "$case" = rank_invariance ]; then
  scene=("${BOX[@]}" -load_schedule 0,1,0.1,1.2 -end_step 300)
  for n in 1 2 3 4; do run $n "$work/np$n" "${scene[@]}"; done
  head -1 "$work/np1/history.csv" | grep -q "right_reaction_z_N,right_nominal_stress_Pa,p_ux_m,p_uy_m,p_uz_m," ||
    fail "history.csv has no z columns: $(head -1 "$work/np1/history.csv")"
  head -1 "$work/np1/final_state.csv" | grep -q "^natural_id,x_m,y_m,z_m,ux_m,uy_m,uz_m$" || fail "final_state.csv has no z columns"
  ux=$(history_column "$work/np1" 300 p_ux_m)
  $PYTHON -c "import sys; sys.exit(0 if float('$ux') > 1e-4 else 1)" || fail "the probe did not move with the grip (ux = $ux m)"
  compare "$work/np1" "$work/np2" "$work/np3" "$work/np4"
elif [ "$case" = failure ]; then
  scene=("${BOX[@]}" -load_schedule 0,1,0.1,1.5 -failure_critical_stretch 1.15 -end_step 200)
  for n in 1 2; do run $n "$work/np$n" "${scene[@]}"; done
  compare --expect-broken "$work/np1" "$work/np2"
  echo "broken bonds at step 200: $(history_column "$work/np1" 200 broken_bonds)"
  # The fracture-energy criterion in 3D (pair energies, the 3D crossing density), on 1 and 3 ranks.
  scene=("${BOX[@]}" -load_schedule 0,1,0.1,1.5 -failure_fracture_energy 0.5 -end_step 200)
  for n in 1 3; do run $n "$work/energy_np$n" "${scene[@]}"; done
  compare --expect-broken "$work/energy_np1" "$work/energy_np3"
  echo "fracture energy: broken bonds at step 200: $(history_column "$work/energy_np1" 200 broken_bonds)"
elif [ "$case" = restart ]; then
  scene=("${BOX[@]}" -load_schedule 0,1,0.1,1.2 -output_fields -output_fields_interval 100)
  N=150
  checkpointed_runs "$work" $N $((2 * N)) "${scene[@]}"
  compare "$work/whole" "$work/second_np2"
  compare "$work/whole" "$work/second_np3"
  last=$(printf "fields/step_%08d.h5" $((2 * N)))
  for d in second_np2 second_np3; do
    $PYTHON "$BAPD_SOURCE_DIR/tests/mpi/restart/compare_fields.py" --tolerance 0 "$work/whole/$last" "$work/$d/$last"
  done
elif [ "$case" = ogden ]; then
  # A fixed step for both laws (no re-estimate): the power iteration's estimate, which
  # stops at a tolerance, moves with the round-off of either law by ~1e-9 and with it
  # every row (measured: dt 7e-10 apart, p_uy 3e-8), which is not what is compared here.
  scene=("${BOX[@]}" -load_schedule 0,1,0.1,1.2 -end_step 300 -time_step 1.5e-4 -time_step_reestimate 0)
  run 1 "$work/neo_hookean" "${scene[@]}" -material_model neo_hookean
  run 2 "$work/ogden_alpha2" "${scene[@]}" -material_model ogden -material_ogden_mu1 4.55e3 -material_ogden_alpha1 2 \
    -material_ogden_mu2 0
  run 1 "$work/ogden_default" "${scene[@]}" -material_model ogden
  grep -q "material  ogden, 3D" "$work/ogden_alpha2.log" || fail "the Ogden run does not say its law"
  # The pull's reactions, the probe, the energies (history) and every displacement (final
  # state), each relative to its largest value; the held components' reactions are
  # round-off (1e-17 N): not compared.
  $PYTHON - "$work" <<'PY' || fail "one-term Ogden (alpha 2) is not the neo-Hookean run, or the two-term Ogden is"
import csv, sys
w = sys.argv[1]
def table(run, name):
    return list(csv.DictReader(open(f"{w}/{run}/{name}")))
def worst(a, b, keys):
    return max(max(abs(float(x[k]) - float(y[k])) for x, y in zip(a, b)) / max(abs(float(x[k])) for x in a) for k in keys)
KEYS = ["left_reaction_x_N", "right_reaction_x_N", "p_ux_m", "p_uy_m", "p_uz_m", "kinetic_energy_J", "internal_energy_J"]
ref = table("neo_hookean", "history.csv")
alpha2, default = table("ogden_alpha2", "history.csv"), table("ogden_default", "history.csv")
ref_final, alpha2_final = table("neo_hookean", "final_state.csv"), table("ogden_alpha2", "final_state.csv")
same = max(worst(ref, alpha2, KEYS), worst(ref_final, alpha2_final, ["ux_m", "uy_m", "uz_m"]))
apart = worst(ref, default, ["right_reaction_x_N"])
print(f"one-term Ogden against neo-Hookean: {same:.2e} (tolerance 1e-10); two-term Ogden's reaction: {apart:.2e} off (> 1e-4 needed)")
sys.exit(0 if len(ref) == len(alpha2) == len(default) and same <= 1e-10 and apart > 1e-4 else 1)
PY
  echo "box_3d ogden: one-term Ogden (alpha 2) = neo-Hookean to 1e-10; the two-term Ogden differs"; exit 0
elif [ "$case" = graded_cloud ]; then
  # x y z volume block: coarse x in [0, 8] mm (block 2: its first column), fine x in
  # [8, 16] mm (block 3: its last column), y in [0, 6], z in [0, 4] mm.
  # graded_cloud FILE GAP: the two blocks with the fine one GAP m further along x.
  graded_cloud() {
    $PYTHON - "$1" "$2" <<'PY'
import sys
rows, gap = [], float(sys.argv[2])
for h, x0, nx, ny, nz in ((2e-3, 0.0, 4, 3, 2), (1e-3, 8e-3 + gap, 8, 6, 4)):
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                block = 2 if h > 1e-3 and i == 0 else 3 if h == 1e-3 and i == nx - 1 else 1
                rows.append((x0 + (i + 0.5) * h, (j + 0.5) * h, (k + 0.5) * h, h ** 3, block))
with open(sys.argv[1], "w") as f:
    f.write("x y z volume block_id\n")
    for r in rows: f.write("%.17g %.17g %.17g %.17g %d\n" % r)
PY
  }
  graded_cloud "$work/graded.txt" 0
  # The rule, pair by pair: delta_i = 3.015 cbrt(V_i), bonded iff |x_j - x_i| <= max(delta_i, delta_j)
  # (no squared distance lies within 0.9 % of a squared horizon here: the count is exact).
  read -r expected single < <($PYTHON - "$work/graded.txt" <<'PY'
import math, sys
p = [tuple(map(float, l.split()[:4])) for l in open(sys.argv[1]).readlines()[1:]]
d = [3.015 * math.cbrt(v) for *_, v in p]
def bonds(reach):
    return sum(1 for i, a in enumerate(p) for j, b in enumerate(p)
               if i != j and sum((a[r] - b[r]) ** 2 for r in range(3)) <= reach(i, j) ** 2)
print(bonds(lambda i, j: max(d[i], d[j])), bonds(lambda i, j: min(d)))
PY
)
  scene=(-body_dimension 3 -body_cloud "$work/graded.txt" -horizon_factor 3.015 -material_mu 4.55e3 -material_Jm 162.6
         -material_bulk_ratio 10 -material_density 1000 -load_sets left,right -load_left_region block -load_left_block 2
         -load_left_x fixed -load_left_y fixed -load_left_z fixed -load_right_region block -load_right_block 3
         -load_right_x stretch -load_right_y fixed -load_right_z fixed -load_reference_length 0.016 -probes p
         -probe_p_at 0.0115,0.0035,0.0025 -damping 40 -output_interval 20 -progress_interval 100000 -output_final_state
         -load_schedule 0,1,0.1,1.2 -end_step 200)
  for n in 1 2; do run $n "$work/np$n" "${scene[@]}"; done
  grep -qF "horizon   delta_i = 3.015 h_i, h_i = cbrt(V_i) (at least 0.003015 m); a bond where either reaches" "$work/np1.log" ||
    fail "the summary does not state the per-point horizons: $(grep "horizon " "$work/np1.log")"
  for n in 1 2; do
    grep -q "^Body: 216 points, $expected bonds, $n rank" "$work/np$n.log" ||
      fail "np$n: $(grep "^Body:" "$work/np$n.log"), not 216 points and the rule's $expected bonds (one horizon: $single)"
  done
  ux=$(history_column "$work/np1" 200 p_ux_m)
  $PYTHON -c "import sys; sys.exit(0 if float('$ux') > 1e-4 else 1)" || fail "the probe did not move with the grip (ux = $ux m)"
  compare "$work/np1" "$work/np2"
  # Pieces are found on the bond graph, per-point horizons and all: a 4 mm gap is bridged
  # by the coarse horizon (5.5 mm from the last coarse column to the first fine one), a
  # 10 mm gap by none: refused, naming the smaller piece (the coarse block's 24 points).
  graded_cloud "$work/bridged.txt" 4e-3
  run 1 "$work/bridged" "${scene[@]}" -body_cloud "$work/bridged.txt" -end_step 2
  graded_cloud "$work/apart.txt" 10e-3
  # (sigkill timeout 0: mpiexec returns at once after bapd's error exit, tests/faults/bad_input.sh)
  if OMPI_MCA_odls_base_sigkill_timeout=0 mpiexec -n 1 "$BAPD_EXE" "${scene[@]}" -body_cloud "$work/apart.txt" -end_step 2 -output_dir "$work/apart" \
      > "$work/apart.log" 2>&1; then fail "a 3D cloud in two pieces ran"; fi
  grep -qF "apart.txt: the given points fall apart into 2 pieces with no bond between them (the smallest: 24 point(s), e.g. point 0 at (0.001, 0.001, 0.001) m)" \
    "$work/apart.log" || fail "no pieces message: $(grep -i error "$work/apart.log")"
  echo "graded cloud: $expected bonds (one horizon: $single)"
elif [ "$case" = patch_cloud ]; then
  # x y z volume block: 12 x 10 x 10 points 1 mm apart, each moved by up to 0.2 mm along
  # each axis and its volume scaled by 1 +- 20 % (seeded): irregular, with an interior
  # beyond the one-horizon boundary layer. Block 2 the first column, 3 the last.
  $PYTHON - "$work/cloud.txt" <<'PY'
import random, sys
random.seed(21)
h, n = 1e-3, (12, 10, 10)
with open(sys.argv[1], "w") as f:
    f.write("x y z volume block_id\n")
    for k in range(n[2]):
        for j in range(n[1]):
            for i in range(n[0]):
                x = [(c + 0.5) * h + 0.2 * h * random.uniform(-1, 1) for c in (i, j, k)]
                block = 2 if i == 0 else 3 if i == n[0] - 1 else 1
                f.write("%.17g %.17g %.17g %.17g %d\n" % (*x, h ** 3 * (1 + 0.2 * random.uniform(-1, 1)), block))
PY
  scene=(-body_dimension 3 -body_cloud "$work/cloud.txt" -horizon_factor 3.015 -material_mu 4.55e3 -material_Jm 162.6
         -material_bulk_ratio 10 -material_density 1000 -load_sets left,right -load_left_region block -load_left_block 2
         -load_left_x fixed -load_left_y fixed -load_left_z fixed -load_right_region block -load_right_block 3
         -load_right_x stretch -load_right_y fixed -load_right_z fixed -load_reference_length 0.012 -probes p
         -probe_p_at 0.0085,0.0055,0.0045 -damping 40 -output_interval 20 -progress_interval 100000 -output_final_state
         -load_schedule 0,1,0.1,1.2 -end_step 150 -force_form bond_only)
  # -force_patch_correction virial on a 3D cloud (patch_correction.hpp: the setup solve in
  # D = 3, 9 numbers a point shipped with the points): 1 and 2 ranks the same, to the bit.
  for n in 1 2; do run $n "$work/np$n" "${scene[@]}" -force_patch_correction virial; done
  solve=$(grep "^Patch correction virial: " "$work/np1.log") || fail "no patch correction report: $(grep -i patch "$work/np1.log")"
  interior=$(sed -E 's/^Patch correction virial: ([0-9]+) interior points.*/\1/' <<< "$solve")
  [ "$interior" -gt 0 ] || fail "the correction has no interior points: $solve"
  grep -qE "solved on rank 0: [0-9]+ conjugate-gradient iterations, residual" "$work/np1.log" ||
    fail "the setup solve does not print its iterations and residual"
  compare "$work/np1" "$work/np2"
  # auto is virial for given points with the bond-only form, as in 2D; off gives other forces.
  run 1 "$work/auto" "${scene[@]}" -end_step 2
  grep -q "patch correction virial" "$work/auto.log" || fail "auto is not virial on a 3D cloud: $(grep -i "force" "$work/auto.log")"
  run 1 "$work/off" "${scene[@]}" -force_patch_correction off
  if grep -q "Patch correction" "$work/off.log"; then fail "-force_patch_correction off solved a correction"; fi
  a=$(history_column "$work/np1" 150 p_uy_m); b=$(history_column "$work/off" 150 p_uy_m)
  $PYTHON -c "import sys; sys.exit(0 if float('$a') != float('$b') else 1)" || fail "the correction changed nothing (p_uy $a m)"
  echo "patch cloud: $solve; probe u_y at step 150 $a m (off: $b m)"
else
  fail "unknown case '$case'"
fi
echo "box_3d $case: identical"
