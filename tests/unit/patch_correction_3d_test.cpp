// -force_patch_correction on a 3D body (patch_correction.hpp): the setup
// solve compute_patch_correction<3> / compute_virial_patch_correction<3> and the
// kernel's h_ij (nd::add_patch_term<3>, read by ba_force.hpp) make the bond-only
// force pass the affine patch test on an irregular 3D cloud; the virial-keeping one
// keeps each point's virial stress sum_j t_ij (x) xi_ij V_j = P; linear momentum stays
// exact. Through the kernel, as a run forms the forces.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "bapd/core/geometry/geometry.hpp"
#include "bapd/core/kernel/patch_correction.hpp"
#include "unit/kernel_fixtures_3d.hpp"

namespace bapd {
namespace {

using test3d::Body3D;
using test3d::kDx;
using test3d::Mat3d;

constexpr int    kBox    = 16;    // points a side
constexpr double kFactor = 3.015; // delta_i = factor cbrt(V_i) (set_point_horizons)

// A kBox^3 box lattice made irregular: every point moved by up to `jitter` dx along
// each axis and its volume scaled by 1 +- `spread` (seeded), with its own horizon
// (a given cloud's, as BodyPoints sets them), families, V(H) and the tensor-corrected
// bond-only geometry.
Body3D irregular_box(double jitter, double spread, unsigned seed)
{
  Body3D                                 b(kBox);
  std::mt19937                           rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double &x : b.cloud.x) x += jitter * kDx * u(rng);
  for (double &v : b.cloud.volume) v *= 1.0 + spread * u(rng);
  set_point_horizons(&b.cloud, 3, kFactor, 0.0);
  double smallest = b.cloud.horizon[0];
  for (double h : b.cloud.horizon) smallest = std::min(smallest, h);
  b.horizon  = smallest;
  b.families = nd::build_families<3>(b.cloud, b.size(), smallest);
  compute_family_volumes(b.cloud, b.families);
  b.state = BondState(b.families);
  b.set_correction(StressCorrection::tensor);
  return b;
}

// Distance of point i from the nearest face of the box [0, kBox dx]^3.
double face_distance(const Body3D &b, std::size_t i)
{
  double d = 1e300;
  for (int r = 0; r < 3; ++r) d = std::min(d, std::min(b.cloud.x[3 * i + r], kBox * kDx - b.cloud.x[3 * i + r]));
  return d;
}

struct AffineFigures {
  double      interior = 0; // largest |f_i| / sum_j (|t_ij| + |t_ji|) V_j over the deep points
  double      virial   = 0; // largest |sum_j t_ij (x) xi_ij V_j - P| / |P| over every point
  double      momentum = 0; // |sum_i f_i V_i| / sum_i terms_i V_i
  std::size_t deep     = 0; // the points measured for `interior`
};

// The bond-only force under an affine motion (large: stretches, shear, a rotation)
// through the kernel, with the cloud's patch_correction as set.
AffineFigures affine_figures(const Body3D &b)
{
  const Mat3d A = nd::multiply<3>(test3d::rotation(25.0, 1.0, -2.0, 0.5), Mat3d{1.3, 0.1, 0.05, 0.0, 0.9, -0.1, 0.0, 0.0, 1.1});
  const NeoHookean3D        model = test3d::neo_hookean();
  Mat3d                     P;
  EXPECT_EQ(model.stress(A, P), StressStatus::ok);
  const std::vector<double> y = b.affine(A, {1e-3, -2e-3, 5e-4});
  std::vector<double>       t, f;
  const KernelStats         stats = b.forces(ForceForm::bond_only, model, y, t, f);
  EXPECT_EQ(stats.unusable, 0u); // every bond carries force: the virial below is P everywhere
  AffineFigures out;
  double        m[3] = {0, 0, 0}, mscale = 0;
  // The boundary layer (lambda = mu = 0) is the edge points (the outer row: a point a
  // spacing deep has bonds straight out) and every point bonded to one, one horizon
  // deeper. Beyond 1.5 horizons (the largest delta_i) every point is the solve's interior.
  const double deep = 1.5 * *std::max_element(b.cloud.horizon.begin(), b.cloud.horizon.end());
  for (std::size_t i = 0; i < b.size(); ++i) {
    const double terms = b.force_terms(t, i);
    for (int r = 0; r < 3; ++r) m[r] += f[3 * i + r] * b.cloud.volume[i];
    mscale += terms * b.cloud.volume[i];
    Mat3d v{};
    for (std::size_t q = b.families.offsets[i]; q < b.families.offsets[i + 1]; ++q) {
      const std::size_t j = static_cast<std::size_t>(b.families.neighbour[q]);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) v[3 * r + c] += t[3 * q + r] * (b.cloud.x[3 * j + c] - b.cloud.x[3 * i + c]) * b.cloud.volume[j];
    }
    for (int k = 0; k < 9; ++k) v[k] -= P[k];
    out.virial = std::max(out.virial, test3d::norm(v) / test3d::norm(P));
    if (face_distance(b, i) <= deep) continue;
    ++out.deep;
    out.interior = std::max(out.interior, std::sqrt(f[3 * i] * f[3 * i] + f[3 * i + 1] * f[3 * i + 1] + f[3 * i + 2] * f[3 * i + 2]) / terms);
  }
  out.momentum = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]) / mscale;
  return out;
}

void print(const char *what, const AffineFigures &a, const PatchCorrectionReport *r)
{
  std::printf("%-22s deep-interior force %.3g of its terms (%zu points), virial error %.3g, momentum %.2g", what, a.interior,
              a.deep, a.virial, a.momentum);
  if (r)
    std::printf("; solve: %zu interior points, %zu CG iterations, residual %.2g, patch defect %.3g -> %.3g, virial change %.3g",
                r->interior, r->iterations, r->residual, r->before, r->after, r->virial);
  std::printf("\n");
}

TEST(PatchCorrection3D, PassesThePatchTestAndKeepsTheVirialOnAnIrregularCloud)
{
  struct Cloud {
    const char *name;
    double      jitter, spread;
  };
  for (const Cloud &c : {Cloud{"jittered 0.2 dx", 0.2, 0.0}, Cloud{"jittered, volumes +-30 %", 0.2, 0.3}}) {
    SCOPED_TRACE(c.name);
    Body3D b = irregular_box(c.jitter, c.spread, 21);

    const AffineFigures off = affine_figures(b); // the defect the correction removes
    print(c.name, off, nullptr);
    EXPECT_GT(off.interior, 0.01);
    EXPECT_GT(off.deep, 50u);
    EXPECT_LT(off.virial, 1e-11); // the tensor correction: P at every point, without patch terms

    PatchCorrectionReport on_report;
    b.cloud.patch_correction = compute_patch_correction<3>(b.cloud, b.families, StressCorrection::tensor, &on_report);
    b.cloud.patch_virial     = false;
    ASSERT_EQ(b.cloud.patch_correction.size(), 3 * b.size()); // lambda: 3 a point
    const AffineFigures on = affine_figures(b);
    print("  on", on, &on_report);
    EXPECT_LT(on.interior, 1e-10);
    EXPECT_LT(on.momentum, 1e-13);
    EXPECT_GT(on.virial, 1e-3); // lambda moves the virial (what virial is for)
    EXPECT_LT(on_report.after, 1e-12);
    EXPECT_GE(on_report.interior, on.deep);

    PatchCorrectionReport virial_report;
    b.cloud.patch_correction = compute_virial_patch_correction<3>(b.cloud, b.families, StressCorrection::tensor, &virial_report);
    b.cloud.patch_virial     = true;
    ASSERT_EQ(b.cloud.patch_correction.size(), nd::patch_stride<3>(true) * b.size()); // mu, S: 9 a point
    const AffineFigures vir = affine_figures(b);
    print("  virial", vir, &virial_report);
    EXPECT_LT(vir.interior, 1e-10);
    EXPECT_LT(vir.virial, 1e-11);
    EXPECT_LT(vir.momentum, 1e-13);
    EXPECT_LT(virial_report.after, 1e-12);
    EXPECT_GE(virial_report.interior, vir.deep);
  }
}

TEST(PatchCorrection3D, RefusesFamiliesThatAreNotTheWholeCloud)
{
  Body3D   b = irregular_box(0.2, 0.0, 5);
  Families part = nd::build_families<3>(b.cloud, b.size() / 2, b.horizon);
  EXPECT_THROW(compute_patch_correction<3>(b.cloud, part, StressCorrection::tensor), std::invalid_argument);
  EXPECT_THROW(compute_virial_patch_correction<3>(b.cloud, part, StressCorrection::tensor), std::invalid_argument);
}

} // namespace
} // namespace bapd
