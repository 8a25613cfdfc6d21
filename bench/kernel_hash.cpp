// A fingerprint of the nd force kernel's results, to show that a change to the kernel
// keeps every bit (docs/notes/performance-kernel-3.md 1j): FNV-1a of the bytes of t_ij, f_i, c33, the
// evaluated count, largest tr C and the strain energy, over
//   3D box lattices at 2.0, 3.015, 3.5, 4.2 dx (mask words 1, 2, 3, 5: the compile-time
//      and the run-time word counts), 0, 5, 30 % of the bonds broken, small and large
//      noise (the large one makes the lane model fail on up to 702 bonds), six kernels
//      (Gent3D scalar and Compressible3DLanes; bond-only, tensor-corrected, energy-consistent);
//   2D lattices at 2.015, 3.015, 4.5 dx, 0 and 10 % broken, Gent plane stress, both
//      forms and the correction, cold then warm c33.
// Build it from two revisions and diff the outputs (bench/CMakeLists.txt: kernel_hash):
//   build/bench/kernel_hash > new.txt; OLD/build/bench/kernel_hash > old.txt; diff old.txt new.txt
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>
#include "bapd/core/geometry/family.hpp"
#include "bapd/core/materials/gent.hpp"
#include "bapd/core/geometry/lattice.hpp"
#include "bapd/core/materials/material.hpp"
#include "bapd/core/materials/plane_stress.hpp"
#include "bapd/core/kernel/ba_force.hpp"
#include "bapd/core/materials/compressible_lanes.hpp"
using namespace bapd;
static std::uint64_t fnv(const void *p, std::size_t n, std::uint64_t h = 1469598103934665603ull)
{
  const unsigned char *c = static_cast<const unsigned char *>(p);
  for (std::size_t k = 0; k < n; ++k) h = (h ^ c[k]) * 1099511628211ull;
  return h;
}
template <class V> std::uint64_t hv(const V &v, std::uint64_t h = 1469598103934665603ull) { return fnv(v.data(), v.size() * sizeof(v[0]), h); }

template <int D> void breaks(const Families &fam, BondState &st, unsigned seed, double frac)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  for (std::size_t i = 0; i < fam.n_family; ++i)
    for (std::size_t q = 0; q < fam.size(i); ++q)
      if (u(rng) < frac && st.is_intact(i, q)) break_bond(fam, st, i, q);
}

// What every case needs beside the points (whose family volumes it sets): the bond state with `frac` of
// the bonds broken (seeded), and the bond geometry without and with the tensor
// correction.
template <int D> struct Case {
  BondState           state;
  nd::BondGeometry<D> geo, cor;
  Case(PointCloud &cloud, const Families &fam, unsigned seed, double frac) : state(fam)
  {
    compute_family_volumes(cloud, fam);
    breaks<D>(fam, state, seed, frac);
    nd::compute_bond_geometry<D>(cloud, fam, state, geo);
    cor.stress_correction = StressCorrection::tensor;
    nd::compute_bond_geometry<D>(cloud, fam, state, cor);
  }
};

int main()
{
  MaterialParameters p;
  p.D = 2.0 / (1000.0 * p.mu);
  std::uint64_t all = 1469598103934665603ull;
  // 3D
  for (double factor : {2.0, 3.015, 3.5, 4.2})
    for (double brk : {0.0, 0.05, 0.3})
      for (double amp : {0.05, 0.6}) {
        const int side = factor > 4 ? 11 : 12;
        const double dx = 5e-4;
        PointCloud cloud = nd::box_lattice<3>({side, side - 1, side - 2}, dx);
        const Families fam = nd::build_families<3>(cloud, cloud.size(), factor * dx);
        Case<3>        c(cloud, fam, 7, brk);
        std::mt19937 rng(3);
        std::uniform_real_distribution<double> noise(-1.0, 1.0);
        std::vector<double> y(cloud.x.size());
        const double stretch[3] = {1.2, 0.9, 1.1};
        for (std::size_t k = 0; k < y.size(); ++k) y[k] = stretch[k % 3] * cloud.x[k] + amp * dx * noise(rng);
        const Gent3D gent{p};
        const nd::Compressible3DLanes<Gent> lanes{ParametersOf<Gent>(p)};
        std::vector<double> t(3 * fam.n_bonds()), f(3 * cloud.size());
        nd::Workspace<3> ws;
        std::uint64_t h = 1469598103934665603ull;
        std::size_t failed = 0;
        for (int v = 0; v < 6; ++v) {
          std::fill(t.begin(), t.end(), -7.0);
          const ForceForm form = v % 3 == 2 ? ForceForm::energy_consistent : ForceForm::bond_only;
          const nd::BondGeometry<3> &g = v % 3 == 1 ? c.cor : c.geo;
          KernelStats s = v < 3 ? nd::compute_bond_forces<3>(form, gent, cloud, y.data(), fam, g, c.state, nullptr, t.data(), ws)
                                : nd::compute_bond_forces<3>(form, lanes, cloud, y.data(), fam, g, c.state, nullptr, t.data(), ws);
          nd::assemble_force_density<3>(fam, cloud, t.data(), cloud.size(), f.data());
          failed += s.failed();
          h = hv(t, h);
          h = hv(f, h);
          h = fnv(&s.evaluated, sizeof s.evaluated, h);
          h = fnv(&s.largest_trC, sizeof s.largest_trC, h);
        }
        const double e = nd::strain_energy<3>(gent, cloud, y.data(), fam, c.geo, c.state, nullptr, cloud.size(), ws);
        h = fnv(&e, sizeof e, h);
        std::printf("3D factor %.3f words %zu break %.2f amp %.2f failed %zu: %016llx\n", factor, fam.mask_words, brk, amp, failed,
                    (unsigned long long)h);
        all = fnv(&h, 8, all);
      }
  // 2D
  for (double factor : {2.015, 3.015, 4.5})
    for (double brk : {0.0, 0.1}) {
      const double dx = 1e-3;
      Body<2> body;
      body.width = 40 * dx; body.height = 30 * dx; body.thickness = 1e-3; body.dx = dx;
      PointCloud cloud = make_lattice(body);
      const Families fam = build_families(cloud, cloud.size(), factor * dx, body.notches);
      Case<2>        c(cloud, fam, 11, brk);
      std::mt19937 rng(1);
      std::uniform_real_distribution<double> noise(-1.0, 1.0);
      std::vector<double> y(cloud.x.size());
      for (std::size_t i = 0; i < cloud.size(); ++i) {
        y[2 * i] = 1.5 * cloud.x[2 * i] + 0.05 * dx * noise(rng);
        y[2 * i + 1] = 0.8 * cloud.x[2 * i + 1] + 0.05 * dx * noise(rng);
      }
      p.mu = 4.55e3; p["-material_Jm"] = 162.6;
      const GentPlaneStress gent{p};
      std::vector<double> t(2 * fam.n_bonds()), f(2 * cloud.size()), c33(fam.n_bonds(), 0.0);
      nd::Workspace<2> ws;
      std::uint64_t h = 1469598103934665603ull;
      for (int v = 0; v < 3; ++v)
        for (int warm = 0; warm < 2; ++warm) {
          const ForceForm form = v == 2 ? ForceForm::energy_consistent : ForceForm::bond_only;
          KernelStats s = nd::compute_bond_forces<2>(form, gent, cloud, y.data(), fam, v == 1 ? c.cor : c.geo, c.state, c33.data(), t.data(), ws);
          nd::assemble_force_density<2>(fam, cloud, t.data(), cloud.size(), f.data());
          h = hv(t, h); h = hv(f, h); h = hv(c33, h);
          h = fnv(&s.evaluated, sizeof s.evaluated, h);
          h = fnv(&s.largest_trC, sizeof s.largest_trC, h);
        }
      const double e = nd::strain_energy<2>(gent, cloud, y.data(), fam, c.geo, c.state, c33.data(), cloud.size(), ws);
      h = fnv(&e, sizeof e, h);
      std::printf("2D factor %.3f words %zu break %.2f: %016llx\n", factor, fam.mask_words, brk, (unsigned long long)h);
      all = fnv(&h, 8, all);
    }
  std::printf("ALL %016llx\n", (unsigned long long)all);
}
