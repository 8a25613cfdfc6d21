// odd_even_modes: the interior stiffness of the bond-associated kernel for a
// displacement along y that varies along y only, u_y = cos(k y / dx), at every k from 0
// to pi (the odd-even, period-2 field), in 2D plane strain or 3D (compressible Gent,
// the paper's gel with K = 10 mu): the kernel's symbol S(k), in mu / dx^2, measured as
// -df_y / du at the centre point of a box (15 cells a side: the centre's force reads
// nothing of the surface at horizons up to 3.515 dx with either force form; the
// energy-consistent force reaches two horizons). The continuum's is (K + 4 mu / 3) k^2.
// odd_even.sh turns S(k) into the decay per row of a static disturbance (the grips'
// boundary layer, docs/validation.md section 6).
//   odd_even_modes D horizon_factor energy|bond_only    -> lines "k S(k)", k = j pi / 32
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bapd/core/geometry/family.hpp"
#include "bapd/core/materials/gent.hpp"
#include "bapd/core/materials/material.hpp"
#include "bapd/core/kernel/ba_force.hpp"

namespace {

constexpr double kDx = 1e-3;
constexpr int    kCells = 15;

template <int D, class Model> int symbol(const Model &model, double factor, bapd::ForceForm form, double mu)
{
  using namespace bapd;
  std::array<int, D> cells;
  cells.fill(kCells);
  PointCloud cloud = nd::box_lattice<D>(cells, kDx);
  Families   fam   = nd::build_families<D>(cloud, cloud.size(), factor * kDx);
  compute_family_volumes(cloud, fam);
  BondState           state(fam);
  nd::BondGeometry<D> geo;
  // The bond-only form as the driver sets it (-force_stress_correction auto: tensor).
  if (form == ForceForm::bond_only) geo.stress_correction = StressCorrection::tensor;
  nd::compute_bond_geometry<D>(cloud, fam, state, geo);
  const std::size_t n = cloud.size(), centre = (n - 1) / 2; // the middle cell (odd kCells)
  nd::Workspace<D>    ws;
  std::vector<double> t(D * fam.n_bonds());
  // f_y of the centre only: the bond forces of the centre and of its family members
  // (ranges of one point), then f_c = sum_j (t_cj - t_jc) V_j (eq 1, assemble_force_density's sum).
  const std::size_t b0 = fam.offsets[centre], b1 = fam.offsets[centre + 1];
  auto force_y = [&](const std::vector<double> &y) {
    nd::compute_bond_forces<D>(form, model, cloud, y.data(), fam, geo, state, nullptr, t.data(), ws, centre, centre + 1);
    for (std::size_t b = b0; b < b1; ++b) {
      const std::size_t j = static_cast<std::size_t>(fam.neighbour[b]);
      nd::compute_bond_forces<D>(form, model, cloud, y.data(), fam, geo, state, nullptr, t.data(), ws, j, j + 1);
    }
    double f = 0.0;
    for (std::size_t b = b0; b < b1; ++b) {
      const std::size_t j = static_cast<std::size_t>(fam.neighbour[b]), r = static_cast<std::size_t>(fam.reverse[b]);
      f += (t[D * b + 1] - t[D * r + 1]) * cloud.volume[j];
    }
    return f;
  };
  const double h = 1e-6 * kDx; // linear, and far above round-off
  for (int j = 0; j <= 32; ++j) {
    const double        k  = j * M_PI / 32.0;
    std::vector<double> yp = cloud.x, ym = cloud.x;
    for (std::size_t i = 0; i < n; ++i) {
      const double u = std::cos(k * (cloud.x[D * i + 1] - cloud.x[D * centre + 1]) / kDx);
      yp[D * i + 1] += h * u;
      ym[D * i + 1] -= h * u;
    }
    const double fp = force_y(yp), fm = force_y(ym);
    std::printf("%.9f %.9e\n", k, -(fp - fm) / (2.0 * h) * kDx * kDx / mu);
  }
  return 0;
}

} // namespace

int main(int argc, char **argv)
{
  if (argc != 4 || (std::string(argv[1]) != "2" && std::string(argv[1]) != "3") ||
      (std::string(argv[3]) != "energy" && std::string(argv[3]) != "bond_only")) {
    std::fprintf(stderr, "usage: odd_even_modes 2|3 horizon_factor energy|bond_only\n");
    return 2;
  }
  const double          factor = std::atof(argv[2]);
  const bapd::ForceForm form =
      std::string(argv[3]) == "energy" ? bapd::ForceForm::energy_consistent : bapd::ForceForm::bond_only;
  bapd::MaterialParameters p; // the paper's gel: mu = 4.55 kPa, Jm = 162.6
  p.D = 2.0 / (10.0 * p.mu);  // K = 10 mu
  if (argv[1][0] == '3') return symbol<3>(bapd::Gent3D{p}, factor, form, p.mu);
  return symbol<2>(bapd::GentPlaneStrain{p}, factor, form, p.mu);
}
