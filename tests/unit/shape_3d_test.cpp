// 3D bodies (shape3d.hpp): lattice counts against the analytic volumes (a box
// exactly, a sphere and a cylinder within the bound a cell-centred lattice must meet),
// the ops in order, planar polygon notches against brute-force counts, bad input, and
// families built on a clipped body.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

#include "bapd/core/geometry/family.hpp"
#include "bapd/core/geometry/shape3d.hpp"

namespace bapd {
namespace {

using nd::Solid;
using P3 = std::array<double, 3>;

constexpr double kDx = 1e-3;

PointCloud points_of(std::vector<Solid> solids, double dx = kDx, std::vector<nd::PlanarPolygon> notches = {})
{
  Body<3> body;
  body.dx      = dx;
  body.solids  = std::move(solids);
  body.notches = std::move(notches);
  return nd::make_solid_points(body);
}

// The message of the std::invalid_argument that make_solid_points throws ("" if none).
std::string error_of(const Body<3> &body)
{
  try {
    nd::make_solid_points(body);
  } catch (const std::invalid_argument &e) {
    return e.what();
  }
  return "";
}

std::set<std::array<long, 3>> cells_of(const PointCloud &c)
{
  std::set<std::array<long, 3>> s;
  for (std::size_t i = 0; i < c.size(); ++i)
    s.insert({std::lround(c.x[3 * i] / kDx - 0.5), std::lround(c.x[3 * i + 1] / kDx - 0.5), std::lround(c.x[3 * i + 2] / kDx - 0.5)});
  return s;
}

double sphere_volume(double r) { return r > 0 ? 4.0 / 3.0 * M_PI * r * r * r : 0.0; }

TEST(Shape3D, BoxIsTheBoxLatticeBitForBit)
{
  // A box [0, n dx] holds exactly the cells of box_lattice<3>, in its order, with its
  // coordinates (the same arithmetic: 0 + (i + 0.5) dx).
  const PointCloud c = points_of({nd::make_box({0, 0, 0}, {10 * kDx, 6 * kDx, 4 * kDx})});
  const PointCloud b = nd::box_lattice<3>({10, 6, 4}, kDx);
  ASSERT_EQ(c.size(), 240u);
  EXPECT_EQ(c.x, b.x);
  EXPECT_EQ(c.volume, b.volume);
  EXPECT_EQ(c.natural_id, b.natural_id);
  EXPECT_DOUBLE_EQ(c.volume[0], kDx * kDx * kDx);

  // Shifted by the origin: the same count, a box of any corner on the grid.
  Body<3> body;
  body.dx     = kDx;
  body.origin = {0.3 * kDx, -2.7 * kDx, 5.1 * kDx};
  body.solids = {nd::make_box(body.origin, {body.origin[0] + 7 * kDx, body.origin[1] + 3 * kDx, body.origin[2] + 5 * kDx})};
  EXPECT_EQ(nd::make_solid_points(body).size(), 105u);
}

// A cell whose centre lies in a convex solid lies in the solid grown by h = sqrt(3)/2 dx
// (half its diagonal); a cell inside the solid shrunk by h has its centre inside. So the
// lattice volume n dx^3 lies between the shrunk and the grown solid's volumes: a bound
// from the geometry, which shrinks linearly with dx.
TEST(Shape3D, SphereVolumeWithinTheLatticeBoundAtTwoSpacings)
{
  const double R = 6.3 * kDx;
  const P3     centre{0.2 * kDx, -0.1 * kDx, 0.35 * kDx}; // off the grid's symmetry
  double       previous_error = 0;
  for (double dx : {kDx, 0.5 * kDx}) {
    const double h      = std::sqrt(3.0) / 2 * dx;
    const double volume = static_cast<double>(points_of({nd::make_sphere(centre, R)}, dx).size()) * dx * dx * dx;
    EXPECT_GE(volume, sphere_volume(R - h)) << dx;
    EXPECT_LE(volume, sphere_volume(R + h)) << dx;
    const double error = std::fabs(volume / sphere_volume(R) - 1);
    std::printf("sphere R = %.1f dx0: dx = %g, relative volume error %.2e (bound %.2e)\n", R / kDx, dx, error,
                sphere_volume(R + h) / sphere_volume(R) - 1);
    if (previous_error > 0) {
      EXPECT_LT(error, previous_error) << "the error must shrink with dx";
    }
    previous_error = error;
  }
}

TEST(Shape3D, CylinderVolumeWithinTheLatticeBoundAtTwoSpacings)
{
  // A tilted axis, so that no lattice line runs along it.
  const double R = 3.7 * kDx;
  const P3     a{-4.1 * kDx, 0.3 * kDx, -2.2 * kDx}, b{5.2 * kDx, 3.9 * kDx, 6.4 * kDx};
  const double L = std::sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2]));
  EXPECT_NEAR(nd::solid_volume(nd::make_cylinder(a, b, R)), M_PI * R * R * L, 1e-15);
  for (double dx : {kDx, 0.5 * kDx}) {
    const double h      = std::sqrt(3.0) / 2 * dx;
    const double volume = static_cast<double>(points_of({nd::make_cylinder(a, b, R)}, dx).size()) * dx * dx * dx;
    EXPECT_GE(volume, M_PI * (R - h) * (R - h) * (L - 2 * h)) << dx;
    EXPECT_LE(volume, M_PI * (R + h) * (R + h) * (L + 2 * h)) << dx;
    std::printf("cylinder R = %.1f dx0, L = %.1f dx0: dx = %g, relative volume error %.2e\n", R / kDx, L / kDx, dx,
                std::fabs(volume / (M_PI * R * R * L) - 1));
  }
}

TEST(Shape3D, BoxWithACylindricalHoleCountsColumnByColumn)
{
  // A cylinder along z through a 20^3 box, its caps outside: each of the 20 layers
  // loses the same disc of cells, counted here in 2D by hand.
  const double R = 4.2 * kDx;
  const PointCloud c = points_of({nd::make_box({0, 0, 0}, {20 * kDx, 20 * kDx, 20 * kDx}),
                                  nd::make_cylinder({10 * kDx, 9.7 * kDx, -1 * kDx}, {10 * kDx, 9.7 * kDx, 21 * kDx}, R,
                                                    Solid::Op::subtract)});
  int disc = 0;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) {
      const double x = (i + 0.5 - 10) * kDx, y = (j + 0.5 - 9.7) * kDx;
      disc += x * x + y * y < R * R;
    }
  ASSERT_GT(disc, 40);
  EXPECT_EQ(c.size(), static_cast<std::size_t>(20 * (400 - disc)));
  for (std::size_t i = 0; i < c.size(); ++i) EXPECT_EQ(c.natural_id[i], static_cast<int64_t>(i));
}

TEST(Shape3D, UnionDifferenceIntersectionInOrder)
{
  const Solid box    = nd::make_box({0, 0, 0}, {10 * kDx, 10 * kDx, 10 * kDx});
  const Solid sphere = nd::make_sphere({10.2 * kDx, 5.1 * kDx, 4.8 * kDx}, 4.3 * kDx);
  auto        with   = [](Solid s, Solid::Op op) { return s.op = op, s; };
  const auto  A = cells_of(points_of({box})), B = cells_of(points_of({sphere}));
  const auto  U = cells_of(points_of({box, sphere}));
  const auto  D = cells_of(points_of({box, with(sphere, Solid::Op::subtract)}));
  const auto  I = cells_of(points_of({box, with(sphere, Solid::Op::intersect)}));
  ASSERT_EQ(A.size(), 1000u);
  ASSERT_GT(I.size(), 50u); // the sphere overlaps the box
  ASSERT_LT(I.size(), B.size());
  // Set algebra on the cells, each side from its own lattice.
  EXPECT_EQ(U.size() + I.size(), A.size() + B.size());
  EXPECT_EQ(D.size(), A.size() - I.size());
  for (const auto &p : I) EXPECT_TRUE(A.count(p) && B.count(p) && U.count(p) && !D.count(p));
  for (const auto &p : D) EXPECT_TRUE(A.count(p) && !B.count(p));
  // Order matters: subtracting the sphere from nothing, then adding the box, is the box.
  EXPECT_EQ(cells_of(points_of({with(sphere, Solid::Op::subtract), box})), A);
  // A box added after the subtraction fills part of the hole again (it reaches the
  // material at x = 5.5 dx: a plug inside the hole alone would be a second piece).
  const Solid plug = nd::make_box({5 * kDx, 4 * kDx, 4 * kDx}, {10 * kDx, 6 * kDx, 6 * kDx});
  auto        DP   = D;
  for (const auto &p : cells_of(points_of({plug}))) DP.insert(p);
  ASSERT_GT(DP.size(), D.size());
  EXPECT_EQ(cells_of(points_of({box, with(sphere, Solid::Op::subtract), plug})), DP);
}

TEST(Shape3D, TetrahedraOfABoxHoldItsPoints)
{
  // A box cut into Kuhn's six tetrahedra (one per order of the axes, all sharing the
  // diagonal lo-hi): the mesh solid keeps exactly the box's points, even those on the
  // inner faces (x = y etc. pass through cell centres: faces are inclusive), and its
  // volume is the box's.
  const P3 lo{0, 0, 0}, hi{6 * kDx, 5 * kDx, 4 * kDx};
  auto     mesh   = std::make_shared<nd::TetrahedronSet>();
  const int axes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto &order : axes) {
    P3 v = lo;
    mesh->corners.insert(mesh->corners.end(), v.begin(), v.end());
    for (int step = 0; step < 3; ++step) {
      v[order[step]] = hi[order[step]];
      mesh->corners.insert(mesh->corners.end(), v.begin(), v.end());
    }
  }
  nd::index_tetrahedra(*mesh);
  EXPECT_NEAR(nd::solid_volume(nd::make_mesh(mesh)), 120 * kDx * kDx * kDx, 1e-12 * 120 * kDx * kDx * kDx);
  EXPECT_EQ(points_of({nd::make_mesh(mesh)}).x, points_of({nd::make_box(lo, hi)}).x);
  // Just outside a face, and a corner (inclusive).
  EXPECT_FALSE(nd::tetrahedra_contain(*mesh, P3{6.0001 * kDx, 2 * kDx, 2 * kDx}.data()));
  EXPECT_TRUE(nd::tetrahedra_contain(*mesh, hi.data()));
}

// The brute-force rule of a notch on the plane x = c, the rectangle (y0, y1) x (z0, z1):
// the end points strictly on opposite sides, the crossing point strictly inside.
bool crosses_rectangle(const double *a, const double *b, double c, double y0, double y1, double z0, double z1)
{
  if (!((a[0] - c) * (b[0] - c) < 0)) return false;
  const double t = (c - a[0]) / (b[0] - a[0]), y = a[1] + t * (b[1] - a[1]), z = a[2] + t * (b[2] - a[2]);
  return y > y0 && y < y1 && z > z0 && z < z1;
}

// The bonds of `cut` are those of `full` minus the ones `crosses` says; counts them.
template <class Crosses> std::size_t expect_cut_bonds(const PointCloud &c, double horizon, const nd::BondCut &cut, Crosses crosses)
{
  const Families full = nd::build_families<3>(c, c.size(), horizon);
  const Families some = nd::build_families<3>(c, c.size(), horizon, cut);
  std::size_t    cut_count = 0, mismatches = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    std::set<int32_t> kept(some.neighbour.begin() + some.offsets[i], some.neighbour.begin() + some.offsets[i + 1]);
    for (std::size_t p = full.offsets[i]; p < full.offsets[i + 1]; ++p) {
      const std::size_t j     = static_cast<std::size_t>(full.neighbour[p]);
      const bool        gone  = !kept.count(static_cast<int32_t>(j));
      const bool        brute = crosses(&c.x[3 * i], &c.x[3 * j]);
      mismatches += gone != brute;
      if (gone != brute && mismatches < 4) // the first few, in dx
        ADD_FAILURE() << "bond (" << c.x[3 * i] / kDx << ", " << c.x[3 * i + 1] / kDx << ", " << c.x[3 * i + 2] / kDx
                      << ") - (" << c.x[3 * j] / kDx << ", " << c.x[3 * j + 1] / kDx << ", " << c.x[3 * j + 2] / kDx
                      << "): cut " << gone << ", brute force " << brute;
      cut_count += gone;
    }
  }
  EXPECT_EQ(mismatches, 0u);
  EXPECT_EQ(some.neighbour.size() + cut_count, full.neighbour.size());
  return cut_count / 2; // each bond twice
}

TEST(Shape3D, ThroughThicknessNotchCutsExactlyTheBondsCrossingIt)
{
  // A 12 x 10 x 4 box, the notch on the cell faces' plane x = 6 dx, from below the box
  // to y = 4.37 dx (off every crossing point of a lattice bond), through the thickness.
  const double     c = 6 * kDx, y1 = 4.37 * kDx;
  nd::PlanarPolygon notch{{c, -kDx, -kDx, c, y1, -kDx, c, y1, 5 * kDx, c, -kDx, 5 * kDx}};
  ASSERT_EQ(nd::planar_polygon_problem(notch), "");
  const PointCloud body = points_of({nd::make_box({0, 0, 0}, {12 * kDx, 10 * kDx, 4 * kDx})}, kDx, {notch});
  const std::size_t cut =
      expect_cut_bonds(body, 3.015 * kDx, nd::polygon_notches({notch}), [&](const double *a, const double *b) {
        return crosses_rectangle(a, b, c, -kDx, y1, -kDx, 5 * kDx);
      });
  EXPECT_GT(cut, 500u);
  std::printf("through-thickness notch: %zu bonds cut\n", cut);

  // A notch inside the thickness (z in (1.2, 2.6) dx): fewer bonds, again exactly those.
  nd::PlanarPolygon inner{{c, -kDx, 1.2 * kDx, c, y1, 1.2 * kDx, c, y1, 2.6 * kDx, c, -kDx, 2.6 * kDx}};
  const std::size_t inner_cut =
      expect_cut_bonds(body, 3.015 * kDx, nd::polygon_notches({inner}), [&](const double *a, const double *b) {
        return crosses_rectangle(a, b, c, -kDx, y1, 1.2 * kDx, 2.6 * kDx);
      });
  EXPECT_GT(inner_cut, 0u);
  EXPECT_LT(inner_cut, cut);
}

TEST(Shape3D, TiltedTriangleNotchAgainstMollerTrumbore)
{
  // A triangle on a tilted plane, checked against an independent segment-triangle test
  // (barycentric coordinates by Moller-Trumbore, strict inequalities). Its vertices are
  // off the lattice's simple fractions, so that no bond meets its boundary (where the
  // two tests, both strict, may round apart).
  const P3 v0{2.313 * kDx, 1.127 * kDx, 0.711 * kDx}, v1{8.937 * kDx, 2.371 * kDx, 3.073 * kDx}, v2{4.191 * kDx, 7.733 * kDx, 2.917 * kDx};
  nd::PlanarPolygon tri{{v0[0], v0[1], v0[2], v1[0], v1[1], v1[2], v2[0], v2[1], v2[2]}};
  ASSERT_EQ(nd::planar_polygon_problem(tri), "");
  auto moller_trumbore = [&](const double *a, const double *b) {
    const P3 d{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e1{v1[0] - v0[0], v1[1] - v0[1], v1[2] - v0[2]},
        e2{v2[0] - v0[0], v2[1] - v0[1], v2[2] - v0[2]};
    const P3     p{d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2], d[0] * e2[1] - d[1] * e2[0]};
    const double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (det == 0) return false; // parallel to the plane
    const P3     s{a[0] - v0[0], a[1] - v0[1], a[2] - v0[2]};
    const double u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) / det;
    const P3     q{s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2], s[0] * e1[1] - s[1] * e1[0]};
    const double v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) / det;
    const double t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
    return u > 0 && v > 0 && u + v < 1 && t > 0 && t < 1;
  };
  const PointCloud  body = points_of({nd::make_box({0, 0, 0}, {10 * kDx, 9 * kDx, 4 * kDx})});
  const std::size_t cut  = expect_cut_bonds(body, 3.015 * kDx, nd::polygon_notches({tri}), moller_trumbore);
  EXPECT_GT(cut, 100u);
}

TEST(Shape3D, NotchRuleForBondsThatTouchOrLieInThePlane)
{
  // The unit square in z = 0 (a notch of side 2 dx centred at the origin).
  const nd::PlanarPolygon sq{{-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}};
  auto cuts = [&](P3 a, P3 b) {
    const bool ab = nd::polygon_cuts(sq, a.data(), b.data()), ba = nd::polygon_cuts(sq, b.data(), a.data());
    EXPECT_EQ(ab, ba) << "the rule is symmetric";
    return ab;
  };
  EXPECT_TRUE(cuts({0.2, 0.3, -0.5}, {0.1, -0.2, 0.5}));   // through the inside
  EXPECT_FALSE(cuts({0.2, 0.3, 0.5}, {0.1, -0.2, 1.5}));   // one side only
  EXPECT_FALSE(cuts({-0.5, 0, 0}, {0.5, 0, 0}));           // lying in the plane, inside the polygon
  EXPECT_FALSE(cuts({0.2, 0.3, 0}, {0.2, 0.3, 1}));        // an end point on the notch
  EXPECT_FALSE(cuts({1.0, 0.0, -1}, {1.0, 0.0, 1}));       // through an edge
  EXPECT_FALSE(cuts({1.0, 1.0, -1}, {1.0, 1.0, 1}));       // through a vertex
  EXPECT_FALSE(cuts({1.5, 0.0, -1}, {1.5, 0.0, 1}));       // beside the polygon
  EXPECT_TRUE(cuts({0.999, 0.999, -1}, {0.999, 0.999, 1})); // just inside a corner
  // A non-convex (L-shaped) polygon: its notch is the L, not its hull.
  const nd::PlanarPolygon ell{{0, 0, 0, 2, 0, 0, 2, 1, 0, 1, 1, 0, 1, 2, 0, 0, 2, 0}};
  ASSERT_EQ(nd::planar_polygon_problem(ell), "");
  EXPECT_TRUE(nd::polygon_cuts(ell, P3{0.5, 1.5, -1}.data(), P3{0.5, 1.5, 1}.data()));
  EXPECT_FALSE(nd::polygon_cuts(ell, P3{1.5, 1.5, -1}.data(), P3{1.5, 1.5, 1}.data()));
}

TEST(Shape3D, NotchThatSplitsTheBodyIsAnError)
{
  Body<3> body;
  body.dx     = kDx;
  body.solids = {nd::make_box({0, 0, 0}, {8 * kDx, 6 * kDx, 3 * kDx})};
  // A notch across the whole section (beyond every face) leaves two pieces.
  body.notches = {{{4 * kDx, -kDx, -kDx, 4 * kDx, 7 * kDx, -kDx, 4 * kDx, 7 * kDx, 4 * kDx, 4 * kDx, -kDx, 4 * kDx}}};
  const std::string e = error_of(body);
  EXPECT_NE(e.find("falls apart into 2 pieces"), std::string::npos) << e;
  // Ending it inside the body keeps one piece.
  body.notches[0].vertices[4] = body.notches[0].vertices[7] = 3.4 * kDx;
  EXPECT_EQ(error_of(body), "");
}

TEST(Shape3D, BadInputNamesTheProblem)
{
  auto error = [](std::vector<Solid> solids, double dx = kDx, std::vector<nd::PlanarPolygon> notches = {}) {
    Body<3> body;
    body.dx = dx, body.solids = std::move(solids), body.notches = std::move(notches);
    return error_of(body);
  };
  auto has = [](const std::string &text, const char *word) {
    return text.find(word) != std::string::npos ? ::testing::AssertionSuccess() : ::testing::AssertionFailure() << text;
  };
  const Solid box = nd::make_box({0, 0, 0}, {4 * kDx, 4 * kDx, 4 * kDx});
  EXPECT_EQ(error({box}), "");
  EXPECT_TRUE(has(error({box}, 0.0), "dx must be > 0"));
  EXPECT_TRUE(has(error({box}, -kDx), "dx must be > 0"));
  EXPECT_TRUE(has(error({nd::make_box({0, 0, 0}, {kDx, 0, kDx})}), "solid 1 (box): its side along y must be > 0"));
  EXPECT_TRUE(has(error({box, nd::make_sphere({0, 0, 0}, -1, Solid::Op::subtract)}), "solid 2 (sphere): its radius must be > 0"));
  EXPECT_TRUE(has(error({nd::make_cylinder({0, 0, 0}, {0, 0, 0}, kDx)}), "same point"));
  EXPECT_TRUE(has(error({nd::make_cylinder({0, 0, 0}, {0, 0, kDx}, 0)}), "radius must be > 0"));
  EXPECT_TRUE(has(error({nd::make_sphere({0, 0, 0}, kDx, Solid::Op::subtract)}), "no solid adds material"));
  // A sphere smaller than the cell, between centres: no point.
  EXPECT_TRUE(has(error({nd::make_sphere({0, 0, 0}, 0.4 * kDx)}), "keep no lattice point"));
  // Two spheres apart.
  EXPECT_TRUE(has(error({nd::make_sphere({0, 0, 0}, 2 * kDx), nd::make_sphere({10 * kDx, 0, 0}, 2 * kDx)}),
                  "falls apart into 2 pieces"));
  // Notches: too few vertices, not planar, self-intersecting (a bow tie).
  EXPECT_TRUE(has(error({box}, kDx, {{{0, 0, 0, 1, 0, 0}}}), "notch 1: a polygon needs at least 3 vertices"));
  EXPECT_TRUE(has(error({box}, kDx, {{{0, 0, 0, 1, 0, 0, 1, 1, 0.1, 0, 1, 0}}}), "off the plane"));
  EXPECT_TRUE(has(error({box}, kDx, {{{0, 0, 0, 1, 1, 0, 1, 0, 0, 0, 1, 0}}}), "must not intersect itself"));
  EXPECT_TRUE(has(error({box}, kDx, {{{0, 0, 0, 1, 1, 1, 2, 2, 2}}}), "area is zero"));
  EXPECT_THROW(nd::polygon_notches({{{0, 0, 0, 1, 1, 0, 1, 0, 0, 0, 1, 0}}}), std::invalid_argument);
}

TEST(Shape3D, FamiliesOnABodyWithASphericalHole)
{
  // A 16^3 box with a spherical hole of radius 2.6 dx at its centre: an interior point
  // far from the faces and the hole has the full 122 members at delta = 3.015 dx;
  // points next to the hole lose the hole's cells, exactly as a direct count says.
  const double     delta = 3.015 * kDx;
  const P3         centre{8 * kDx, 8 * kDx, 8 * kDx};
  const PointCloud c     = points_of({nd::make_box({0, 0, 0}, {16 * kDx, 16 * kDx, 16 * kDx}),
                                      nd::make_sphere(centre, 2.6 * kDx, Solid::Op::subtract)});
  const Families   fam   = nd::build_families<3>(c, c.size(), delta);
  EXPECT_EQ(fam.max_family_size, 122u);
  auto direct = [&](std::size_t i) {
    std::size_t n = 0;
    for (std::size_t j = 0; j < c.size(); ++j) {
      const double dx = c.x[3 * j] - c.x[3 * i], dy = c.x[3 * j + 1] - c.x[3 * i + 1], dz = c.x[3 * j + 2] - c.x[3 * i + 2];
      n += j != i && dx * dx + dy * dy + dz * dz <= delta * delta;
    }
    return n;
  };
  std::size_t interior = 0, near_hole = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    double to_face = 1e300, to_centre2 = 0;
    for (int r = 0; r < 3; ++r)
      to_face = std::min({to_face, c.x[3 * i + r], 16 * kDx - c.x[3 * i + r]}),
      to_centre2 += (c.x[3 * i + r] - centre[r]) * (c.x[3 * i + r] - centre[r]);
    const double to_hole = std::sqrt(to_centre2) - 2.6 * kDx;
    if (to_face > delta && to_hole > delta) {
      EXPECT_EQ(fam.size(i), 122u) << i;
      ++interior;
    } else if (to_hole < kDx && to_face > delta) {
      EXPECT_LT(fam.size(i), 122u) << i;
      EXPECT_EQ(fam.size(i), direct(i)) << i;
      ++near_hole;
    }
  }
  EXPECT_GT(interior, 100u);
  EXPECT_GT(near_hole, 20u);
}

} // namespace
} // namespace bapd
