// The plane-stress solve's fast paths (plane_stress.hpp): the warm-started step taken
// without a second evaluation, and the four-bond stress_lanes that the bond kernel
// runs. Both must give what a tightly converged solve gives, to the solve's own
// tolerance, and stress_lanes exactly what stress() gives.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "bapd/core/materials/models.hpp"
#include "materials/deformations.hpp"
#include "materials/law_types.hpp"

namespace bapd {
namespace {

constexpr double mu = 4.55e3, Jm = 162.6;

// C33 with S33 = 0 from the 3D law (an implementation independent of PlaneStress):
// bisection on the sign of S33(F~, sqrt(c)) down to adjacent doubles. A locked c counts
// as S33 = -inf below a/2 and +inf above (as in PlaneStress).
template <class Law> double reference_c33(const MaterialParameters &p, const Mat2 &F)
{
  const double a = F[0] * F[0] + F[1] * F[1] + F[2] * F[2] + F[3] * F[3], k = det(F) * det(F);
  // (2k/a: where a law's I2bar term vanishes, plane_stress.hpp; below a/2 and 1/k's bracket otherwise)
  double       lo = std::min({0.5 * a, 1.0 / k, 2.0 * k / a}), hi = std::max(0.5 * a, 1.0 / k);
  for (int it = 0; it < 2000; ++it) {
    const double c = 0.5 * (lo + hi);
    if (!(c > lo && c < hi)) break;
    Mat3       P;
    const auto status = Compressible3D<Law>{p}.stress(embed(F, std::sqrt(c)), P);
    const bool below  = status == StressStatus::ok ? P[8] < 0.0 : c < 0.5 * a;
    (below ? lo : hi) = c;
  }
  return 0.5 * (lo + hi);
}

// |S33| / (the terms of C33 S33 that cancel, over C33, + mu): the round-off scale.
template <class Law> double relative_out_of_plane_stress(const MaterialParameters &p, const Mat2 &F, double c)
{
  const double scale = test::out_of_plane_stress_scale<Law>(p, F, c);
  Mat3         P;
  EXPECT_EQ(Compressible3D<Law>{p}.stress(embed(F, std::sqrt(c)), P), StressStatus::ok);
  return std::abs(P[8] / std::sqrt(c)) / scale;
}

// Loading paths as the explicit solver walks them, to stretch 8 and compression 1/4,
// and towards the Gent limit (uniaxial 12.5: I1bar - 3 within ~5 % of Jm).
std::vector<std::pair<std::string, Mat2>> loading_path(double increment)
{
  std::vector<std::pair<std::string, Mat2>> out;
  const Mat2                                R = test::rotation2(0.4);
  for (double l = 1.0; l < 8.0; l *= 1.0 + increment) out.push_back({"biaxial", R * Mat2{l, 0.1 * (l - 1.0), 0.0, l}});
  for (double l = 1.0; l < 12.5; l *= 1.0 + increment) out.push_back({"uniaxial", R * Mat2{1.0 / std::sqrt(l), 0.0, 0.0, l}});
  for (double l = 1.0; l > 0.25; l /= 1.0 + increment) out.push_back({"compression", R * Mat2{l, 0.0, 0.0, 1.0}});
  for (double g = 0.0; g < 8.0; g += increment) out.push_back({"simple shear", Mat2{1.0, g, 0.0, 1.0}});
  return out;
}

template <class Model> class PlaneStressFastPath : public ::testing::Test {};
using Models = test::InvariantPlaneStressModels;
TYPED_TEST_SUITE(PlaneStressFastPath, Models);


TYPED_TEST(PlaneStressFastPath, WarmStepMatchesTightlyConvergedReferenceAlongLoadingPaths)
{
  using Law = typename test::LawOf<TypeParam>::type;
  for (double K_over_mu : {10.0, 1e3, 1e4}) {
    const MaterialParameters p = test::parameters(mu, Jm, 2.0 / (K_over_mu * mu));
    const TypeParam          model{p};
    // 1e-3 per step: the larger time steps of the solver (|dC33|/C33 up to ~1e-3, the
    // accepted step's limit); 1e-4: the usual ones
    for (double increment : {1e-3, 1e-4}) {
      double      c33 = 0.0, worst_s33 = 0.0, worst_c = 0.0;
      std::string previous;
      int         single = 0, solves = 0;
      for (const auto &[name, F] : loading_path(increment)) {
        if (name != previous) c33 = 0.0; // each path starts cold
        previous                    = name;
        const PlaneStressSolution s = model.solve(F, c33);
        if (s.status != StressStatus::ok) { // Gent: the far end of a path may be locked
          c33 = 0.0;
          continue;
        }
        if (c33 > 0.0) {
          ++solves;
          single += s.evaluations == 1;
        }
        c33 = s.c33;
        if (solves % 7 != 0) continue; // the 3D reference is slow: every 7th point
        const double c_ref = reference_c33<Law>(p, F);
        worst_s33          = std::max(worst_s33, relative_out_of_plane_stress<Law>(p, F, s.c33));
        worst_c            = std::max(worst_c, std::abs(s.c33 - c_ref) / c_ref);
      }
      // The solve stops at |C33 S33| <= 1e-13 of the cancelling terms + 1e-12 mu C33 +
      // 4 eps f' C33 (an unevaluated step: its bound on what it leaves is half of that).
      // The last, the round-off floor, is ~4 eps K C33 ~ 4e-12 mu at K = 1e4 mu, and so is
      // the round-off of the 3D S33 (eps K): 1e-11, as in plane_stress_test's sweep. A
      // step taken with a third-order bound at |dC33| ~ 1e-3 C33 would leave ~1e-9.
      EXPECT_LT(worst_s33, 1e-11) << "K/mu " << K_over_mu << " increment " << increment;
      // C33 error = residual / f' ~ the same relative size (f' C33 >= the cancelling terms / 3)
      EXPECT_LT(worst_c, 1e-11) << "K/mu " << K_over_mu << " increment " << increment;
      // not vacuous: warm-started solves end with the unevaluated step, all but those
      // whose |dC33| / C33 is above 1e-3 (biaxial: 4x the stretch increment)
      EXPECT_GT(single, (increment < 1e-3 ? 0.9 : 0.5) * solves) << "K/mu " << K_over_mu << " increment " << increment;
      ::testing::Test::RecordProperty("worst_relative_S33", std::to_string(worst_s33));
    }
  }
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// stress_lanes in a register of W lanes (T: Lanes, or HalfLanes for a point's last few
// bonds) against stress() lane by lane.
template <class Model, class T> void expect_lanes_give_bit_for_bit_the_scalar_stress()
{
  constexpr int W = sizeof(T) / sizeof(double);
  std::mt19937  rng(23);
  for (double K_over_mu : {10.0, 1e3, 1e4}) {
    const Model model{test::parameters(mu, Jm, 2.0 / (K_over_mu * mu))};
    int         done_lanes = 0, lanes = 0;
    for (int group = 0; group < 400; ++group) {
      std::array<Mat2, W>   F;
      std::array<double, W> guess;
      for (int l = 0; l < W; ++l) {
        F[l]                        = test::random_F2(rng, l == W - 1 && group % 2 ? 12.0 : 4.0);
        const PlaneStressSolution s = model.solve(F[l], 0.0);
        // warm starts from exact to 1e-2 away, none, and garbage
        const double spread[] = {0.0, 1e-7, 1e-5, 1e-4, 1e-3, 1e-2};
        guess[l] = s.status != StressStatus::ok ? 1.0 : s.c33 * (1.0 + spread[rng() % 6] * test::uniform(rng, -1.0, 1.0));
        if (group % 17 == 0) guess[l] = l == 0 ? 0.0 : l == 1 ? -1.0 : l == 2 ? 1e300 : guess[l];
      }
      if (group % 23 == 0) F[1] = {1.0, 2.0, 2.0, 1.0}; // inverted
      double by_component[4][W];
      for (int l = 0; l < W; ++l)
        for (int comp = 0; comp < 4; ++comp) by_component[comp][l] = F[l][comp];
      std::array<T, 4> FL, PL;
      T                c;
      for (int comp = 0; comp < 4; ++comp) std::memcpy(&FL[comp], by_component[comp], sizeof(T));
      std::memcpy(&c, guess.data(), sizeof(T));
      const auto done = model.stress_lanes(FL, c, PL);
      for (int l = 0; l < W; ++l) {
        ++lanes;
        double             cs = guess[l];
        Mat2               P;
        const StressStatus status = model.stress(F[l], cs, P);
        if (!done[l]) {
          EXPECT_TRUE(same_bits(c[l], guess[l])) << "a lane not done keeps its warm start";
          continue;
        }
        ++done_lanes;
        ASSERT_EQ(status, StressStatus::ok);
        EXPECT_TRUE(same_bits(c[l], cs)) << c[l] << " " << cs;
        for (int comp = 0; comp < 4; ++comp) EXPECT_TRUE(same_bits(PL[comp][l], P[comp])) << PL[comp][l] << " " << P[comp];
      }
    }
    EXPECT_GT(done_lanes, lanes / 2); // not vacuous: the close warm starts finish in the lanes
    EXPECT_LT(done_lanes, lanes);     // and some (garbage, inverted, far) do not
  }
}

// Every lane of the register (4 with AVX2, 8 with AVX-512).
TYPED_TEST(PlaneStressFastPath, LanesGiveBitForBitTheScalarStress)
{
  expect_lanes_give_bit_for_bit_the_scalar_stress<TypeParam, Lanes>();
}

// Half a register (2 or 4 lanes): a point's last bonds in the kernel (model_lanes).
TYPED_TEST(PlaneStressFastPath, HalfRegisterGivesBitForBitTheScalarStress)
{
  expect_lanes_give_bit_for_bit_the_scalar_stress<TypeParam, HalfLanes>();
}

} // namespace
} // namespace bapd
