// -force_patch_correction through the whole driver (patch_correction.hpp,
// docs/discretisations.md): a jittered cloud with unequal volumes read from a file, set
// up by Simulation (rank 0's setup solve, the per-point numbers shipped with the points
// to their ranks and ring-1 ghosts, the nd:: kernel), under an affine motion u = A X.
// Every bond then has F_ij = I + A and one P, so
//   - an interior point's force density must vanish (the affine patch test): with on
//     and virial, not with off (the uncorrected discrete divergence of a constant P);
//   - every point's nominal stress, the virial sum_j t_ij (x) xi_ij V_j with the tensor
//     correction (point_quantities.hpp), must be P: with off and virial, not with on
//     (lambda's central terms move it by a few percent at single points);
//   - linear momentum holds with each;
//   - the forces and stresses are the same bits on any rank count: each run on N ranks
//     is compared, by natural id and with tolerance 0, with the same scene set up on
//     rank 0 alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "bapd/core/materials/models.hpp"
#include "bapd/core/kernel/point_quantities.hpp"
#include "bapd/solver/driver/simulation.hpp"
#include "mpi/test_scenes.hpp"

using namespace bapd;

namespace {

constexpr int    kSide = 30;     // points a side
constexpr double kDx   = 5e-4;   // m
constexpr double kT    = 1e-3;   // thickness, m
const double     kA[4] = {0.20, 0.05, -0.10, -0.08}; // u = A X (row-major)

// The cloud of NonUniformPatch's jittered clouds (tests/unit/geometry_test.cpp): a
// kSide^2 lattice, each point moved by up to 0.2 dx per axis and its volume scaled by
// 1 +- 0.3 (so each point's own horizon 3.015 sqrt(V/t) differs too). A fixed
// linear-congruential sequence: the same file on every machine.
void WriteJitteredCloud(const std::string &path)
{
  std::uint64_t state = 12345;
  auto          next  = [&]() { // in [-1, 1)
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 4503599627370496.0 - 1.0;
  };
  std::ofstream out(path);
  out.precision(17);
  out << "x,y,volume\n";
  for (int r = 0; r < kSide; ++r)
    for (int c = 0; c < kSide; ++c) {
      const double x = (c + 0.5 + 0.2 * next()) * kDx, y = (r + 0.5 + 0.2 * next()) * kDx;
      out << x << ',' << y << ',' << kDx * kDx * kT * (1.0 + 0.3 * next()) << '\n';
    }
}

std::string CloudScene(const std::string &cloud, const char *correction, const std::string &output_dir)
{
  return "-body_cloud " + cloud + " -body_thickness 0.001 -horizon_factor 3.015 -material_model gent "
         "-material_mu 4.55e3 -material_Jm 162.6 -material_bulk_ratio 100 -material_density 1000 -end_time 1 "
         "-force_form bond_only -force_stress_correction tensor -force_patch_correction " +
         std::string(correction) + " -output_dir " + bapd_test::OutputDirPerRankCount(output_dir) +
         " -output_interval 1000000 -progress_interval 1000000";
}

// Force density (2) and nominal stress (4) of every owned point under u = A X, with
// the points' natural ids.
struct Affine {
  std::vector<int64_t> id;
  std::vector<double>  x, force, stress, volume;
};

Affine Evaluate(Simulation &sim)
{
  const Layout  &layout = sim.layout();
  const PetscInt n      = layout.n_owned;
  Affine         a;
  std::vector<double> u(2 * n);
  for (PetscInt i = 0; i < n; ++i) {
    const double X = layout.cloud.x[2 * i], Y = layout.cloud.x[2 * i + 1];
    u[2 * i]       = kA[0] * X + kA[1] * Y;
    u[2 * i + 1]   = kA[2] * X + kA[3] * Y;
    a.id.push_back(layout.cloud.natural_id[i]);
    a.x.insert(a.x.end(), {X, Y});
    a.volume.push_back(layout.cloud.volume[i]);
  }
  a.force.resize(2 * n);
  PointQuantities q;
  EXPECT_EQ(sim.ComputePointQuantities(u.data(), a.force.data(), &q), 0);
  a.stress.assign(q.nominal_stress.begin(), q.nominal_stress.begin() + 4 * n);
  return a;
}

// Every rank's values on rank 0, ordered by natural id.
std::vector<double> GatherByNaturalId(MPI_Comm comm, const std::vector<int64_t> &id, const std::vector<double> &v, int width)
{
  int rank, size;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int        n = static_cast<int>(id.size());
  std::vector<int> counts(size), displs(size);
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  int total = 0;
  for (int r = 0; r < size; ++r) displs[r] = total, total += counts[r];
  std::vector<int64_t> all_id(total);
  MPI_Gatherv(id.data(), n, MPI_INT64_T, all_id.data(), counts.data(), displs.data(), MPI_INT64_T, 0, comm);
  for (int r = 0; r < size; ++r) counts[r] *= width, displs[r] *= width;
  std::vector<double> all(static_cast<std::size_t>(width) * total), ordered(all.size());
  MPI_Gatherv(v.data(), width * n, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE, 0, comm);
  for (int k = 0; k < total && rank == 0; ++k)
    for (int c = 0; c < width; ++c) ordered[width * all_id[k] + c] = all[width * k + c];
  return ordered;
}

} // namespace

TEST(PatchCorrectionDriver, AffineMotionOnAJitteredCloud)
{
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const std::string cloud = "patch_correction_driver_cloud.csv";
  if (rank == 0) WriteJitteredCloud(cloud);
  MPI_Barrier(PETSC_COMM_WORLD);

  struct Case {
    const char *correction;
    bool        patch_test, virial; // which must hold
  } cases[] = {{"off", false, true}, {"on", true, false}, {"virial", true, true}};
  for (const Case &c : cases) {
    ASSERT_EQ(bapd_test::SetOptions(CloudScene(cloud, c.correction, "patch_correction_driver_output")), 0);
    Simulation sim(PETSC_COMM_WORLD);
    ASSERT_EQ(sim.Setup(), 0) << c.correction;
    const Affine a = Evaluate(sim);

    // P(I + A), the stress every bond carries.
    const Scene &scene = sim.scene();
    Mat2         P{};
    with_model(scene.material.model, scene.material.formulation, scene.material.parameters, [&](const auto &model) {
      double c33 = 0.0;
      return model.stress(Mat2{1.0 + kA[0], kA[1], kA[2], 1.0 + kA[3]}, c33, P);
    });
    const double Pn = std::sqrt(P[0] * P[0] + P[1] * P[1] + P[2] * P[2] + P[3] * P[3]);

    // Interior: more than three horizons (of the largest spacing, 1.14 dx) from the
    // sheet's edges, as NonUniformPatch's interior_affine_residual.
    const double margin = 3.0 * 3.015 * 1.15 * kDx, side = kSide * kDx;
    double       local[3] = {0, 0, 0}, global[3]; // interior |f|, any |f|, virial error
    double       momentum[2] = {0, 0}, momentum_scale = 0;
    for (std::size_t i = 0; i < a.id.size(); ++i) {
      const double f = std::hypot(a.force[2 * i], a.force[2 * i + 1]), X = a.x[2 * i], Y = a.x[2 * i + 1];
      if (std::min({X, Y, side - X, side - Y}) > margin) local[0] = std::max(local[0], f);
      local[1] = std::max(local[1], f);
      double e = 0.0;
      for (int k = 0; k < 4; ++k) e += (a.stress[4 * i + k] - P[k]) * (a.stress[4 * i + k] - P[k]);
      local[2] = std::max(local[2], std::sqrt(e) / Pn);
      for (int k = 0; k < 2; ++k) momentum[k] += a.force[2 * i + k] * a.volume[i];
      momentum_scale += f * a.volume[i];
    }
    MPI_Allreduce(local, global, 3, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, momentum, 2, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, &momentum_scale, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    const double interior = global[0] / global[1]; // over the edge's traction-bearing force
    PetscPrintf(PETSC_COMM_WORLD, "%-6s largest interior force %.3g of the largest force, largest virial error %.3g of |P|\n",
                c.correction, interior, global[2]);
    ASSERT_GT(global[1], 0.0);
    if (c.patch_test) EXPECT_LT(interior, 1e-12) << c.correction;
    else EXPECT_GT(interior, 1e-2) << c.correction;
    if (c.virial) EXPECT_LT(global[2], 1e-11) << c.correction;
    else EXPECT_GT(global[2], 1e-2) << c.correction;
    EXPECT_LT(std::hypot(momentum[0], momentum[1]), 1e-13 * momentum_scale) << c.correction;

    // The same bits as the scene on rank 0 alone.
    const std::vector<double> force = GatherByNaturalId(PETSC_COMM_WORLD, a.id, a.force, 2),
                              stress = GatherByNaturalId(PETSC_COMM_WORLD, a.id, a.stress, 4);
    if (rank == 0) {
      ASSERT_EQ(bapd_test::SetOptions(CloudScene(cloud, c.correction, "patch_correction_driver_self")), 0);
      Simulation alone(PETSC_COMM_SELF);
      ASSERT_EQ(alone.Setup(), 0) << c.correction;
      const Affine        b = Evaluate(alone);
      std::vector<double> f1(force.size()), s1(stress.size());
      for (std::size_t i = 0; i < b.id.size(); ++i) {
        for (int k = 0; k < 2; ++k) f1[2 * b.id[i] + k] = b.force[2 * i + k];
        for (int k = 0; k < 4; ++k) s1[4 * b.id[i] + k] = b.stress[4 * i + k];
      }
      ASSERT_EQ(f1.size(), 2 * b.id.size());
      std::size_t differ = 0;
      for (std::size_t k = 0; k < force.size(); ++k) differ += force[k] != f1[k];
      for (std::size_t k = 0; k < stress.size(); ++k) differ += stress[k] != s1[k];
      EXPECT_EQ(differ, 0u) << c.correction << ": force or stress values differ from the 1-rank run";
    }
    MPI_Barrier(PETSC_COMM_WORLD);
  }
}
