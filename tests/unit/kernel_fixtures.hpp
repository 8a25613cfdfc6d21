#pragma once
// Scaffolding shared by the bond-kernel tests (ba_force*_test.cpp): a cut and deformed
// plate, the sizes that round-off is measured against, a finite-difference stiffness,
// a geometry with a stress correction, and one rank's scrambled local view of a plate
// for the rank-layout tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include "bapd/core/kernel/damage.hpp"
#include "bapd/core/materials/gent.hpp"
#include "bapd/core/materials/material.hpp"
#include "unit/test_models.hpp"

namespace bapd::test {

inline constexpr double kPlateDx = 0.5e-3; // the dx of plate() and CutPlate

inline Mat2 rotation(double deg)
{
  const double a = deg * 3.141592653589793 / 180.0;
  return {std::cos(a), -std::sin(a), std::sin(a), std::cos(a)};
}

// A large affine map: stretch 3, shear, rotation by 40 degrees.
inline const Mat2 kLargeAffine = rotation(40.0) * Mat2{3.0, 0.5, 0.0, 1.1};

// The paper's hydrogel with K = 100 mu (Gent, plane stress).
inline GentPlaneStress hydrogel()
{
  MaterialParameters p;
  p.D = 2.0 / (100.0 * p.mu);
  return GentPlaneStress{p};
}

// A plate with a hole and a notch, deformed non-affinely (stretch, shear and noise of
// `noise` dx), with every 5th bond of every third point broken.
struct CutPlate {
  Body<2>              body;
  Discretisation      d;
  std::vector<double> y;

  CutPlate(int n, double noise, unsigned seed, double horizon_factor = 3.015)
      : body(make_body(n)), d(body, horizon_factor)
  {
    std::mt19937 rng(seed);
    y = d.affine({1.2, 0.15, -0.1, 0.92});
    for (double &v : y) v += random_between(rng, -noise, noise) * kPlateDx;
    std::vector<std::size_t> touched;
    for (std::size_t i = 0; i < d.size(); i += 3)
      for (std::size_t q = 1; q < d.families.size(i); q += 5) break_bond(d.families, d.state, i, q, &touched);
    nd::compute_bond_geometry<2>(d.cloud, d.families, d.state, d.geometry, touched);
  }
  static Body<2> make_body(int n)
  {
    Body<2> b = plate(n, n, kPlateDx);
    b.holes.push_back({0.3 * n * kPlateDx, 0.6 * n * kPlateDx, 2.5 * kPlateDx});
    b.notches.push_back({n * kPlateDx, 0.5 * n * kPlateDx, 0.55 * n * kPlateDx, 0.5 * n * kPlateDx});
    return b;
  }
};

// sum_j (|t_ij| + |t_ji|) V_j: the size of the terms that cancel in f_i.
inline double force_terms(const Discretisation &d, const std::vector<double> &t, std::size_t i)
{
  double s = 0;
  for (std::size_t b = d.families.offsets[i]; b < d.families.offsets[i + 1]; ++b) {
    const std::size_t r = static_cast<std::size_t>(d.families.reverse[b]);
    s += (std::hypot(t[2 * b], t[2 * b + 1]) + std::hypot(t[2 * r], t[2 * r + 1])) *
         d.cloud.volume[static_cast<std::size_t>(d.families.neighbour[b])];
  }
  return s;
}

// sum_j t_ij (x) xi_ij V_j of point i from the bond forces t: the stress the bonds carry
// (P wherever the force is stress-consistent, stress_correction.hpp).
inline Mat2 bond_force_virial(const Discretisation &d, const std::vector<double> &t, std::size_t i)
{
  Mat2 V = {0.0, 0.0, 0.0, 0.0};
  for (std::size_t b = d.families.offsets[i]; b < d.families.offsets[i + 1]; ++b) {
    const std::size_t j  = static_cast<std::size_t>(d.families.neighbour[b]);
    const double      d0 = d.cloud.x[2 * j] - d.cloud.x[2 * i], d1 = d.cloud.x[2 * j + 1] - d.cloud.x[2 * i + 1];
    const double      v  = d.cloud.volume[j];
    V = V + Mat2{t[2 * b] * d0 * v, t[2 * b] * d1 * v, t[2 * b + 1] * d0 * v, t[2 * b + 1] * d1 * v};
  }
  return V;
}

// Over the usable bonds: the largest |F_ij - A| / |A| of the motion y (affine with A),
// and how many bonds are usable.
inline double worst_affine_gradient_error(const Discretisation &d, const std::vector<double> &y, const Mat2 &A, std::size_t *usable)
{
  double worst = 0;
  *usable      = 0;
  for (std::size_t i = 0; i < d.size(); ++i)
    for (std::size_t q = 0; q < d.families.size(i); ++q) {
      if (!d.geometry.is_usable(i, q)) continue;
      ++*usable;
      const Mat2 F = nd::bond_deformation_gradient<2>(d.cloud, y.data(), d.families, d.geometry, d.state, i, q);
      worst        = std::max(worst, norm(F - A) / norm(A));
    }
  return worst;
}

inline double max_abs(const std::vector<double> &v)
{
  double m = 0;
  for (double a : v) m = std::max(m, std::abs(a));
  return m;
}

// The largest |t_b| over the bonds of a bond-force array t.
inline double max_abs_force(const std::vector<double> &t)
{
  double m = 0;
  for (std::size_t b = 0; 2 * b < t.size(); ++b) m = std::max(m, std::hypot(t[2 * b], t[2 * b + 1]));
  return m;
}

// The distance of point i of d from the edges of a width x height plate.
inline double boundary_distance(const Discretisation &d, std::size_t i, double width, double height)
{
  const double x = d.cloud.x[2 * i], y = d.cloud.x[2 * i + 1];
  return std::min(std::min(x, width - x), std::min(y, height - y));
}

// The net force of the points of a side x side plate at least `reach` from its edges
// (the interior), relative to the size of their terms, against the boundary's.
struct InteriorForce {
  std::size_t interior     = 0; // how many points are interior
  double      worst        = 0; // the largest |f_i| / force_terms there
  double      boundary_max = 0; // the same over the other points
};
inline InteriorForce interior_force(const Discretisation &d, const std::vector<double> &t, const std::vector<double> &f, double side,
                                    double reach)
{
  InteriorForce r;
  for (std::size_t i = 0; i < d.size(); ++i) {
    const double rel = std::hypot(f[2 * i], f[2 * i + 1]) / force_terms(d, t, i);
    if (boundary_distance(d, i, side, side) >= reach) {
      ++r.interior;
      r.worst = std::max(r.worst, rel);
    } else r.boundary_max = std::max(r.boundary_max, rel);
  }
  return r;
}

// The geometry of d recomputed with a stress correction (-force_stress_correction).
inline void set_correction(Discretisation &d, StressCorrection c)
{
  d.geometry.stress_correction = c;
  nd::compute_bond_geometry<2>(d.cloud, d.families, d.state, d.geometry);
}

// Largest |K_rs - K_sr| / max |K| over the stiffness entries K_rs = -d f_r / d u_s of
// the given points, forces(y, f) giving the force density (central differences at
// u = 0; equal volumes, so V K is the Hessian of W where an energy exists).
template <class Forces>
double stiffness_asymmetry(const Discretisation &d, const std::vector<std::size_t> &points, Forces forces)
{
  const double                     h = 1e-6 * d.cloud.x[0];
  std::vector<std::vector<double>> column(2 * points.size());
  for (std::size_t s = 0; s < 2 * points.size(); ++s) {
    std::vector<double> fp, fm, y = d.cloud.x;
    y[2 * points[s / 2] + s % 2] += h;
    forces(y, fp);
    y[2 * points[s / 2] + s % 2] -= 2 * h;
    forces(y, fm);
    for (std::size_t k = 0; k < fp.size(); ++k) fp[k] = (fp[k] - fm[k]) / (2 * h);
    column[s] = fp;
  }
  double asym = 0, size = 0;
  for (std::size_t r = 0; r < 2 * points.size(); ++r)
    for (std::size_t s = 0; s < 2 * points.size(); ++s) {
      const double k_rs = column[s][2 * points[r / 2] + r % 2], k_sr = column[r][2 * points[s / 2] + s % 2];
      asym = std::max(asym, std::abs(k_rs - k_sr));
      size = std::max(size, std::abs(k_rs));
    }
  return asym / size;
}

// One rank's view: owned points, ring-1 ghosts (bonded to an owned point), ring-2
// ghosts (bonded to a ring-1 one), each group shuffled, with the global V(H) shipped.
struct LocalView {
  PointCloud               cloud;
  std::size_t              n_owned = 0, n_family = 0;
  std::vector<std::size_t> global; // local -> global index
};

inline LocalView local_view(const PointCloud &g, const Families &gf, const std::vector<bool> &owned, std::mt19937 &rng)
{
  const std::size_t        n = g.size();
  std::vector<int>         ring(n, -1);
  std::vector<std::size_t> groups[3];
  for (std::size_t i = 0; i < n; ++i)
    if (owned[i]) ring[i] = 0, groups[0].push_back(i);
  for (int r = 1; r <= 2; ++r)
    for (std::size_t i : std::vector<std::size_t>(groups[r - 1]))
      for (std::size_t b = gf.offsets[i]; b < gf.offsets[i + 1]; ++b) {
        const std::size_t j = static_cast<std::size_t>(gf.neighbour[b]);
        if (ring[j] < 0) ring[j] = r, groups[r].push_back(j);
      }
  LocalView v;
  for (auto &grp : groups) {
    std::shuffle(grp.begin(), grp.end(), rng);
    v.global.insert(v.global.end(), grp.begin(), grp.end());
  }
  v.n_owned  = groups[0].size();
  v.n_family = groups[0].size() + groups[1].size();
  for (std::size_t gi : v.global) {
    v.cloud.x.push_back(g.x[2 * gi]);
    v.cloud.x.push_back(g.x[2 * gi + 1]);
    v.cloud.volume.push_back(g.volume[gi]);
    v.cloud.natural_id.push_back(g.natural_id[gi]);
    v.cloud.family_volume.push_back(g.family_volume[gi]); // shipped by the solver
  }
  return v;
}

// A 24 x 24 plate with a hole and a notch, deformed with noise, bonds broken by
// stretch, split into two scrambled "ranks": each rank's owned force densities, and its
// ring-1 ghosts' bond forces and C33, must be bit for bit the one-rank ones.
// kernel(cloud, y, families, geometry, state, c33, bond_force, ws) is the bond kernel.
// correction: -force_stress_correction of both geometries (stress_correction.hpp).
template <class Kernel>
void expect_rank_local_views_reproduce_one_rank(Kernel kernel, StressCorrection correction = StressCorrection::none)
{
  const double dx   = kPlateDx;
  Body<2>       body = plate(24, 24, dx);
  body.holes.push_back({7.0 * dx, 15.0 * dx, 2.5 * dx});
  body.notches.push_back({24 * dx, 12.0 * dx, 14.0 * dx, 12.0 * dx});
  Discretisation      d(body);
  d.geometry.stress_correction = correction;
  nd::compute_bond_geometry<2>(d.cloud, d.families, d.state, d.geometry);
  std::mt19937        rng(3);
  std::vector<double> y = d.affine({1.4, 0.1, 0.0, 0.95});
  for (double &v : y) v += random_between(rng, -0.15, 0.15) * dx;
  const double s_c = 1.45;
  // One rank: break by stretch, recompute, forces.
  std::vector<std::size_t> touched;
  ASSERT_GT(nd::break_bonds<2>(d.cloud, y.data(), d.families, s_c, d.state, touched), 10u);
  nd::compute_bond_geometry<2>(d.cloud, d.families, d.state, d.geometry, touched);
  std::vector<double> t(2 * d.families.n_bonds(), 0.0), f(2 * d.size(), 0.0), c33(d.families.n_bonds(), 0.0);
  {
    nd::Workspace<2> ws;
    ASSERT_TRUE(kernel(d.cloud, y.data(), d.families, d.geometry, d.state, c33.data(), t.data(), ws).ok());
    nd::assemble_force_density<2>(d.families, d.cloud, t.data(), d.size(), f.data());
  }
  // Two "ranks": a band and its complement, in scrambled local orders.
  for (int part = 0; part < 2; ++part) {
    std::vector<bool> owned(d.size());
    for (std::size_t i = 0; i < d.size(); ++i)
      owned[i] = ((d.cloud.x[2 * i] + 0.5 * d.cloud.x[2 * i + 1]) < 14 * dx) == (part == 0);
    LocalView           v  = local_view(d.cloud, d.families, owned, rng);
    Families            lf = build_families(v.cloud, v.n_family, d.horizon, body.notches);
    BondState           ls(lf);
    std::vector<double> ly(2 * v.cloud.size());
    for (std::size_t k = 0; k < v.global.size(); ++k) ly[2 * k] = y[2 * v.global[k]], ly[2 * k + 1] = y[2 * v.global[k] + 1];
    std::vector<std::size_t> lt;
    nd::break_bonds<2>(v.cloud, ly.data(), lf, s_c, ls, lt);
    nd::BondGeometry<2> lg;
    lg.stress_correction = correction;
    nd::compute_bond_geometry<2>(v.cloud, lf, ls, lg);
    std::vector<double> lbf(2 * lf.n_bonds()), lfd(2 * v.n_owned), lc33(lf.n_bonds(), 0.0);
    nd::Workspace<2> ws;
    kernel(v.cloud, ly.data(), lf, lg, ls, lc33.data(), lbf.data(), ws);
    nd::assemble_force_density<2>(lf, v.cloud, lbf.data(), v.n_owned, lfd.data());
    for (std::size_t k = 0; k < v.n_owned; ++k) {
      const std::size_t gi = v.global[k];
      ASSERT_EQ(lfd[2 * k], f[2 * gi]) << "natural id " << gi; // bit for bit
      ASSERT_EQ(lfd[2 * k + 1], f[2 * gi + 1]) << "natural id " << gi;
    }
    for (std::size_t k = 0; k < v.n_family; ++k) // ring-1 ghosts' bond forces and c33 too
      for (std::size_t q = 0; q < lf.size(k); ++q) {
        const std::size_t gb = d.families.offsets[v.global[k]] + q, lb = lf.offsets[k] + q;
        ASSERT_EQ(lbf[2 * lb], t[2 * gb]);
        ASSERT_EQ(lbf[2 * lb + 1], t[2 * gb + 1]);
        ASSERT_EQ(lc33[lb], c33[gb]);
      }
  }
}

} // namespace bapd::test
