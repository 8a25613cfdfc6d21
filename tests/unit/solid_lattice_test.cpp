// The summary of a 3D lattice body found without its points (shape3d.hpp,
// solid_lattice): its count, extent and pieces against the built points
// (append_solid_layers, body_pieces) on bodies cut into pieces by solids and notches,
// bit for bit. (Its memory: scene_3d_test.cpp, ReadingALatticeHoldsNoPoints.)
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <limits>
#include <random>
#include <vector>

#include "bapd/core/geometry/shape3d.hpp"

namespace bapd {
namespace {

using nd::Solid;
using P3 = std::array<double, 3>;

constexpr double kDx = 1e-3;

// What solid_lattice must give, from the built points.
nd::SolidLattice from_points(const Body<3> &body)
{
  PointCloud c;
  nd::append_solid_layers(body, 0, nd::solid_layers(body), &c, nullptr);
  nd::SolidLattice s;
  s.points = static_cast<int64_t>(c.size());
  s.lo.fill(std::numeric_limits<double>::max());
  s.hi.fill(-std::numeric_limits<double>::max());
  for (std::size_t p = 0; p < c.size(); ++p)
    for (int r = 0; r < 3; ++r)
      s.lo[r] = std::min(s.lo[r], c.x[3 * p + r] - 0.5 * body.dx), s.hi[r] = std::max(s.hi[r], c.x[3 * p + r] + 0.5 * body.dx);
  s.pieces = nd::body_pieces(body, c);
  return s;
}

::testing::AssertionResult same(const nd::SolidLattice &a, const nd::SolidLattice &b)
{
  if (a.points != b.points || a.lo != b.lo || a.hi != b.hi || a.pieces.count != b.pieces.count ||
      a.pieces.smallest_points != b.pieces.smallest_points || a.pieces.smallest_at != b.pieces.smallest_at)
    return ::testing::AssertionFailure() << a.points << " points, " << a.pieces.count << " pieces (smallest " << a.pieces.smallest_points
                                         << " at " << a.pieces.smallest_at[0] << ", " << a.pieces.smallest_at[1] << ", "
                                         << a.pieces.smallest_at[2] << ") against " << b.points << ", " << b.pieces.count << " ("
                                         << b.pieces.smallest_points << " at " << b.pieces.smallest_at[0] << ", "
                                         << b.pieces.smallest_at[1] << ", " << b.pieces.smallest_at[2] << ")";
  return ::testing::AssertionSuccess();
}

// Bodies whose pieces join and part in every direction of the pass: a U whose arms meet
// only in a later layer, spheres apart and touching, rings, and notches through the body.
TEST(SolidLattice, CountExtentAndPiecesAreThoseOfTheBuiltPoints)
{
  std::vector<Body<3>> bodies(4);
  for (Body<3> &b : bodies) b.dx = kDx;
  // An arch: two legs (z < 5 dx), two pieces to the pass until the top joins them.
  bodies[0].solids = {nd::make_box({0, 0, 0}, {9 * kDx, 3 * kDx, 8 * kDx}),
                      nd::make_box({3 * kDx, -kDx, -kDx}, {6 * kDx, 4 * kDx, 5 * kDx}, Solid::Op::subtract)};
  // Two equal spheres apart, and a third, larger: the smallest is the first in natural order.
  bodies[1].solids = {nd::make_sphere({0, 0, 0}, 2.2 * kDx), nd::make_sphere({8 * kDx, 0, 0}, 2.2 * kDx),
                      nd::make_sphere({0, 9 * kDx, 9 * kDx}, 3.1 * kDx)};
  // A ring (a cylinder less a coaxial one) along y, cut by a notch on its x- side: one
  // piece, whose two ends the pass meets apart and joins on the x+ side.
  bodies[2].solids = {nd::make_cylinder({0, 0, 0}, {0, 4 * kDx, 0}, 5 * kDx),
                      nd::make_cylinder({0, -kDx, 0}, {0, 5 * kDx, 0}, 2.5 * kDx, Solid::Op::subtract)};
  bodies[2].notches = {{{-6 * kDx, -kDx, 0, -kDx, -kDx, 0, -kDx, 5 * kDx, 0, -6 * kDx, 5 * kDx, 0}}};
  // A box cut across by two notches, one tilted: three pieces of 80 points each (the
  // smallest is the first in natural order).
  bodies[3].solids  = {nd::make_box({0, 0, 0}, {12 * kDx, 5 * kDx, 4 * kDx})};
  bodies[3].notches = {{{4 * kDx, -kDx, -kDx, 4 * kDx, 6 * kDx, -kDx, 4 * kDx, 6 * kDx, 5 * kDx, 4 * kDx, -kDx, 5 * kDx}},
                       {{8 * kDx, -kDx, -kDx, 8.5 * kDx, 6 * kDx, -kDx, 8.5 * kDx, 6 * kDx, 5 * kDx, 8 * kDx, -kDx, 5 * kDx}}};
  const int64_t pieces[] = {1, 3, 1, 3};
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const nd::SolidLattice expected = from_points(bodies[k]);
    EXPECT_EQ(expected.pieces.count, pieces[k]) << "body " << k;
    EXPECT_TRUE(same(nd::solid_lattice(bodies[k]), expected)) << "body " << k;
  }
}

// Random unions and differences of spheres and boxes, shifted origins: the same figures.
TEST(SolidLattice, RandomBodiesAgreeWithTheBuiltPoints)
{
  std::mt19937                           random(7);
  std::uniform_real_distribution<double> at(0, 10 * kDx), size(0.8 * kDx, 3 * kDx);
  int                                    apart = 0;
  for (int trial = 0; trial < 40; ++trial) {
    Body<3> b;
    b.dx     = kDx;
    b.origin = {at(random) / 10, at(random) / 10, at(random) / 10};
    for (int s = 0; s < 6; ++s) {
      const Solid::Op op = s == 0 || random() % 3 != 0 ? Solid::Op::add : Solid::Op::subtract;
      const P3        c{at(random), at(random), at(random)};
      if (random() % 2) b.solids.push_back(nd::make_sphere(c, size(random), op));
      else b.solids.push_back(nd::make_box(c, {c[0] + size(random), c[1] + size(random), c[2] + size(random)}, op));
    }
    const nd::SolidLattice expected = from_points(b);
    apart += expected.pieces.count > 1;
    EXPECT_TRUE(same(nd::solid_lattice(b), expected)) << "trial " << trial;
  }
  EXPECT_GT(apart, 10); // most bodies fall apart: the pieces are tested, not only one
}

} // namespace
} // namespace bapd
