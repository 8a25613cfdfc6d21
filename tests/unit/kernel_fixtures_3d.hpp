#pragma once
// Scaffolding of the 3D core tests (family_3d_test.cpp, ba_force_3d_test.cpp): a box
// (or a ball cut from one) of the generic core in D = 3, the paper's gel as the
// compressible 3D Gent and neo-Hookean laws, and the sizes round-off is measured
// against.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "bapd/core/materials/gent.hpp"
#include "bapd/core/materials/material.hpp"
#include "bapd/core/materials/neo_hookean.hpp"
#include "bapd/core/kernel/ba_force.hpp"
#include "bapd/core/geometry/family.hpp"

namespace bapd::test3d {

using Mat3d = nd::Mat<3>;
using Vec3d = nd::Vec<3>;

inline constexpr double kDx = 1e-3;

// The paper's hydrogel (mu = 4.55 kPa, Jm = 162.6) with K = 100 mu.
inline MaterialParameters gel()
{
  MaterialParameters p;
  p.D = 2.0 / (100.0 * p.mu);
  return p;
}
inline Gent3D       gent() { return Gent3D{gel()}; }
inline NeoHookean3D neo_hookean() { return NeoHookean3D{gel()}; }

// Rotation by `deg` degrees about the axis (a0, a1, a2) (Rodrigues).
inline Mat3d rotation(double deg, double a0, double a1, double a2)
{
  const double n = std::sqrt(a0 * a0 + a1 * a1 + a2 * a2), x = a0 / n, y = a1 / n, z = a2 / n;
  const double t = deg * 3.141592653589793 / 180.0, c = std::cos(t), s = std::sin(t), C = 1.0 - c;
  return {c + x * x * C,     x * y * C - z * s, x * z * C + y * s, y * x * C + z * s, c + y * y * C,
          y * z * C - x * s, z * x * C - y * s, z * y * C + x * s, c + z * z * C};
}

inline double norm(const Mat3d &A)
{
  double s = 0;
  for (double a : A) s += a * a;
  return std::sqrt(s);
}

// Points, families, state and geometry of a 3D body on one rank.
struct Body3D {
  PointCloud          cloud;
  Families            families;
  BondState           state;
  nd::BondGeometry<3> geometry;
  double              horizon = 0;

  // An n x n x n box of side n dx; keep(x) (if given) says which points stay.
  explicit Body3D(int n, double factor = 3.015, const std::function<bool(const double *)> &keep = {})
      : horizon(factor * kDx)
  {
    const PointCloud box = nd::box_lattice<3>({n, n, n}, kDx);
    for (std::size_t i = 0; i < box.size(); ++i) {
      if (keep && !keep(box.x.data() + 3 * i)) continue;
      for (int r = 0; r < 3; ++r) cloud.x.push_back(box.x[3 * i + r]);
      cloud.volume.push_back(box.volume[i]);
      cloud.natural_id.push_back(box.natural_id[i]);
    }
    families = nd::build_families<3>(cloud, cloud.size(), horizon);
    compute_family_volumes(cloud, families);
    state = BondState(families);
    nd::compute_bond_geometry<3>(cloud, families, state, geometry);
  }
  std::size_t size() const { return cloud.size(); }

  void set_correction(StressCorrection c)
  {
    geometry.stress_correction = c;
    nd::compute_bond_geometry<3>(cloud, families, state, geometry);
  }
  // Every `every`-th bond of every third point broken (both copies), geometry redone.
  void break_some(std::size_t every)
  {
    std::vector<std::size_t> touched;
    for (std::size_t i = 0; i < size(); i += 3)
      for (std::size_t q = 1; q < families.size(i); q += every) break_bond(families, state, i, q, &touched);
    nd::compute_bond_geometry<3>(cloud, families, state, geometry, touched);
  }
  // y = A x + c
  std::vector<double> affine(const Mat3d &A, const Vec3d &c = {0.0, 0.0, 0.0}) const
  {
    std::vector<double> y(cloud.x.size());
    for (std::size_t i = 0; i < size(); ++i) {
      const Vec3d x = {cloud.x[3 * i], cloud.x[3 * i + 1], cloud.x[3 * i + 2]}, ax = nd::multiply<3>(A, x);
      for (int r = 0; r < 3; ++r) y[3 * i + r] = ax[r] + c[r];
    }
    return y;
  }
  // A non-affine state: A x plus noise of `noise` dx.
  std::vector<double> deformed(const Mat3d &A, double noise, unsigned seed) const
  {
    std::mt19937        rng(seed);
    std::vector<double> y = affine(A);
    for (double &v : y) v += (static_cast<double>(rng()) / 4294967296.0 - 0.5) * 2.0 * noise * kDx;
    return y;
  }
  template <class Model>
  KernelStats forces(ForceForm form, const Model &model, const std::vector<double> &y, std::vector<double> &t,
                     std::vector<double> &f) const
  {
    nd::Workspace<3> ws;
    t.assign(3 * families.n_bonds(), 0.0);
    const KernelStats s =
        nd::compute_bond_forces<3>(form, model, cloud, y.data(), families, geometry, state, nullptr, t.data(), ws);
    f.assign(3 * size(), 0.0);
    nd::assemble_force_density<3>(families, cloud, t.data(), size(), f.data());
    return s;
  }
  template <class Model> double energy(const Model &model, const std::vector<double> &y) const
  {
    nd::Workspace<3> ws;
    return nd::strain_energy<3>(model, cloud, y.data(), families, geometry, state, nullptr, size(), ws);
  }
  // sum_j (|t_ij| + |t_ji|) V_j: the size of the terms that cancel in f_i.
  double force_terms(const std::vector<double> &t, std::size_t i) const
  {
    double s = 0;
    for (std::size_t b = families.offsets[i]; b < families.offsets[i + 1]; ++b) {
      const std::size_t r = static_cast<std::size_t>(families.reverse[b]);
      s += (std::sqrt(t[3 * b] * t[3 * b] + t[3 * b + 1] * t[3 * b + 1] + t[3 * b + 2] * t[3 * b + 2]) +
            std::sqrt(t[3 * r] * t[3 * r] + t[3 * r + 1] * t[3 * r + 1] + t[3 * r + 2] * t[3 * r + 2])) *
           cloud.volume[static_cast<std::size_t>(families.neighbour[b])];
    }
    return s;
  }
  // Distance of point i from the outermost lattice centres of an n-box, in dx.
  double depth(std::size_t i, int n) const
  {
    double d = 1e300;
    for (int r = 0; r < 3; ++r) {
      const double k = cloud.x[3 * i + r] / kDx - 0.5;
      d              = std::min(d, std::min(k, n - 1 - k));
    }
    return d;
  }
};

} // namespace bapd::test3d
