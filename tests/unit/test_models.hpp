#pragma once
// Test-local constitutive models and a small discretisation builder for the kernel
// tests. The models follow the 2D model interface of material.hpp.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include "bapd/core/kernel/ba_force.hpp"
#include "bapd/core/geometry/body.hpp"
#include "bapd/core/kernel/bond_geometry.hpp"
#include "bapd/core/kernel/bond_state.hpp"
#include "bapd/core/geometry/family.hpp"
#include "bapd/core/geometry/lattice.hpp"
#include "bapd/core/materials/material.hpp"
#include "bapd/core/kernel/tensor.hpp"

namespace bapd::test {

// 2D Saint Venant-Kirchhoff: S = lambda tr(E) I + 2 mu E, E = (F^T F - I)/2, P = F S.
// Objective (depends on F through C only); its small-strain uniaxial-stress modulus
// in 2D is E = 4 mu (lambda + mu) / (lambda + 2 mu), Poisson ratio lambda / (lambda + 2 mu).
struct SaintVenantKirchhoff2D {
  double lambda = 2.0e4, mu = 1.0e4; // [Pa]

  double young_modulus() const { return 4.0 * mu * (lambda + mu) / (lambda + 2.0 * mu); }
  double poisson_ratio() const { return lambda / (lambda + 2.0 * mu); }

  StressStatus stress(const Mat2 &F, double &c33, Mat2 &P) const
  {
    c33 = 1.0;
    if (!(det(F) > 0.0)) {
      P = {};
      return StressStatus::inverted;
    }
    const Mat2   C   = right_cauchy_green(F);
    const Mat2   E   = {0.5 * (C[0] - 1.0), 0.5 * C[1], 0.5 * C[2], 0.5 * (C[3] - 1.0)};
    const double trE = E[0] + E[3];
    const Mat2   S   = {lambda * trE + 2.0 * mu * E[0], 2.0 * mu * E[1], 2.0 * mu * E[2], lambda * trE + 2.0 * mu * E[3]};
    P                = F * S;
    return StressStatus::ok;
  }
  StressStatus energy(const Mat2 &F, double &c33, double &psi) const
  {
    c33 = 1.0;
    if (!(det(F) > 0.0)) return StressStatus::inverted;
    const Mat2   C   = right_cauchy_green(F);
    const Mat2   E   = {0.5 * (C[0] - 1.0), 0.5 * C[1], 0.5 * C[2], 0.5 * (C[3] - 1.0)};
    const double trE = E[0] + E[3];
    psi = 0.5 * lambda * trE * trE + mu * (E[0] * E[0] + E[1] * E[1] + E[2] * E[2] + E[3] * E[3]);
    return StressStatus::ok;
  }
};

// SVK that reports chain_limit once F_xx exceeds a threshold (to exercise the kernel's
// failure path), and writes a recognisable c33 when it succeeds.
struct LimitedModel {
  SaintVenantKirchhoff2D svk;
  double                 max_Fxx = 1.5;
  StressStatus           stress(const Mat2 &F, double &c33, Mat2 &P) const
  {
    if (F[0] > max_Fxx) {
      c33 = -123.0; // garbage the kernel must not store
      P   = {};
      return StressStatus::chain_limit;
    }
    svk.stress(F, c33, P);
    c33 = 0.5;
    return StressStatus::ok;
  }
  StressStatus energy(const Mat2 &F, double &c33, double &psi) const { return svk.energy(F, c33, psi); }
};

// A square-ish plate of nx x ny cells, dx = 0.5 mm, thickness 3 mm (so that volumes
// differ from dx^2 and unit slips show).
inline Body<2> plate(int nx, int ny, double dx = 0.5e-3, double thickness = 3.0e-3)
{
  Body<2> b;
  b.dx        = dx;
  b.width     = nx * dx;
  b.height    = ny * dx;
  b.thickness = thickness;
  return b;
}

// Points, families, state and geometry of a body on one rank.
struct Discretisation {
  PointCloud   cloud;
  Families     families;
  BondState    state;
  nd::BondGeometry<2> geometry;
  double       horizon = 0;

  explicit Discretisation(const Body<2> &body, double horizon_factor = 3.015)
      : cloud(make_lattice(body)), horizon(horizon_factor * body.dx)
  {
    families = build_families(cloud, cloud.size(), horizon, body.notches);
    compute_family_volumes(cloud, families);
    state = BondState(families);
    nd::compute_bond_geometry<2>(cloud, families, state, geometry);
  }
  // Points with their own volumes and horizons (geometry.hpp: make_points of given
  // points), with the stress correction C_i if asked.
  explicit Discretisation(PointCloud points, StressCorrection correction = StressCorrection::none)
      : cloud(std::move(points)), horizon(*std::max_element(cloud.horizon.begin(), cloud.horizon.end()))
  {
    families = build_families(cloud, cloud.size(), horizon, {});
    compute_family_volumes(cloud, families);
    state                       = BondState(families);
    geometry.stress_correction  = correction;
    nd::compute_bond_geometry<2>(cloud, families, state, geometry);
  }
  std::size_t size() const { return cloud.size(); }

  // y = A x + c for every point.
  std::vector<double> affine(const Mat2 &A, double c0 = 0.0, double c1 = 0.0) const
  {
    std::vector<double> y(cloud.x.size());
    for (std::size_t i = 0; i < size(); ++i) {
      const double x0 = cloud.x[2 * i], x1 = cloud.x[2 * i + 1];
      y[2 * i]        = A[0] * x0 + A[1] * x1 + c0;
      y[2 * i + 1]    = A[2] * x0 + A[3] * x1 + c1;
    }
    return y;
  }

  template <class Model> KernelStats forces(const Model &model, const std::vector<double> &y,
                                            std::vector<double> &bond_force, std::vector<double> &f) const
  {
    nd::Workspace<2> ws;
    bond_force.assign(2 * families.n_bonds(), 0.0);
    const KernelStats s = nd::compute_bond_forces<2>(ForceForm::bond_only, model, cloud, y.data(), families, geometry, state, nullptr,
                                              bond_force.data(), ws);
    f.assign(2 * size(), 0.0);
    nd::assemble_force_density<2>(families, cloud, bond_force.data(), size(), f.data());
    return s;
  }

  // The same with the energy-consistent bond forces (ba_force.hpp).
  template <class Model> KernelStats energy_consistent_forces(const Model &model, const std::vector<double> &y,
                                                              std::vector<double> &bond_force,
                                                              std::vector<double> &f) const
  {
    nd::Workspace<2> ws;
    bond_force.assign(2 * families.n_bonds(), 0.0);
    const KernelStats s = nd::compute_bond_forces<2>(ForceForm::energy_consistent, model, cloud, y.data(), families, geometry, state,
                                                                nullptr, bond_force.data(), ws);
    f.assign(2 * size(), 0.0);
    nd::assemble_force_density<2>(families, cloud, bond_force.data(), size(), f.data());
    return s;
  }

  // Lattice index helpers (valid without holes).
  int ix(std::size_t i, double dx) const { return static_cast<int>(std::floor(cloud.x[2 * i] / dx)); }
  int iy(std::size_t i, double dx) const { return static_cast<int>(std::floor(cloud.x[2 * i + 1] / dx)); }
};

// A geometry computed afresh from d's current bond state, with d's stress correction
// (d.geometry itself may be stale on purpose): for the output path (point_quantities).
inline nd::BondGeometry<2> nd_geometry(const Discretisation &d)
{
  nd::BondGeometry<2> g;
  g.stress_correction = d.geometry.stress_correction;
  nd::compute_bond_geometry<2>(d.cloud, d.families, d.state, g);
  return g;
}

// Uniform in [lo, hi) from the raw 32-bit engine output (the same sequence on every
// standard library).
inline double random_between(std::mt19937 &rng, double lo, double hi)
{
  return lo + (hi - lo) * (static_cast<double>(rng()) / 4294967296.0);
}

inline double norm(const Mat2 &A) { return std::sqrt(A[0] * A[0] + A[1] * A[1] + A[2] * A[2] + A[3] * A[3]); }

} // namespace bapd::test
