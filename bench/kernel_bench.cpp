// Kernel benchmark: ns per bond evaluation of compute_bond_forces on a 300 x 300
// lattice (delta = 3.015 dx), and the bytes per point of every per-point and per-bond
// array the kernel and the solver's force evaluation use.
//
// Build from the repository root (Release, host-tuned, like the project), then run:
//   g++ -std=c++17 -O3 -march=native -DNDEBUG -Iinclude -Itests bench/kernel_bench.cpp
//       src/core/*.cpp -o /tmp/kernel_bench
//   /tmp/kernel_bench [n = 300] [horizon_factor = 3.015]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "bapd/ba_force.hpp"
#include "bapd/bond_geometry.hpp"
#include "bapd/family.hpp"
#include "bapd/lattice.hpp"
#include "unit/test_models.hpp"

#if __has_include("bapd/gent.hpp")
#include "bapd/gent.hpp"
#define BENCH_HAVE_GENT 1
#endif

using namespace bapd;

namespace {

// P = F: no constitutive cost, measures the kernel's own work (gather, masked sums,
// K^{-1}, force vector, stores).
struct IdentityStress {
  StressStatus stress(const Mat2 &F, double &, Mat2 &P) const
  {
    P = F;
    return StressStatus::ok;
  }
  StressStatus energy(const Mat2 &, double &, double &psi) const
  {
    psi = 0;
    return StressStatus::ok;
  }
};

template <class Model>
void time_kernel(const char *name, const Model &model, const PointCloud &cloud, const std::vector<double> &y,
                 const Families &fam, const BondGeometry &geo, const BondState &state, bool warm_start)
{
  std::vector<double> c33(fam.n_bonds(), 0.0), t(2 * fam.n_bonds());
  BondKernelWorkspace ws;
  KernelStats         s = compute_bond_forces(model, cloud, y.data(), fam, geo, state, warm_start ? c33.data() : nullptr,
                                              t.data(), ws); // warm up, fill c33
  const int           reps = 20;
  double              best = 1e300, sum = 0;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    s = compute_bond_forces(model, cloud, y.data(), fam, geo, state, warm_start ? c33.data() : nullptr, t.data(), ws);
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    best = std::min(best, sec);
    sum += sec;
  }
  double checksum = 0;
  for (double v : t) checksum += v;
  std::printf("%-34s %7.2f ns/bond (best), %7.2f mean, %6.1f M bonds/s, failed %zu, checksum %.6e\n", name,
              1e9 * best / static_cast<double>(s.evaluated), 1e9 * sum / reps / static_cast<double>(s.evaluated),
              static_cast<double>(s.evaluated) / best / 1e6, s.failed(), checksum);
}

} // namespace

int main(int argc, char **argv)
{
  const int    n      = argc > 1 ? std::atoi(argv[1]) : 300;
  const double factor = argc > 2 ? std::atof(argv[2]) : 3.015;
  const double dx     = 1e-3;
  const Body2D body   = test::plate(n, n, dx, 1e-3);

  auto             t0    = std::chrono::steady_clock::now();
  PointCloud       cloud = make_lattice(body);
  const Families   fam   = build_families(cloud, cloud.size(), factor * dx, body.notches);
  compute_family_volumes(cloud, fam);
  const BondState  state(fam);
  BondGeometry     geo;
  compute_bond_geometry(cloud, fam, state, geo);
  const double setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double np = static_cast<double>(cloud.size()), nb = static_cast<double>(fam.n_bonds());
  std::printf("%d x %d lattice, delta = %.3f dx: %zu points, %zu bonds (%.2f per point), mask words %zu; setup %.3f s\n",
              n, n, factor, cloud.size(), fam.n_bonds(), nb / np, fam.mask_words, setup);

  // A moderately large, non-affine deformation: stretch 1.5 x 0.8 plus 5 % dx noise.
  std::mt19937        rng(1);
  std::vector<double> y(cloud.x.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    y[2 * i]     = 1.5 * cloud.x[2 * i] + test::random_between(rng, -0.05, 0.05) * dx;
    y[2 * i + 1] = 0.8 * cloud.x[2 * i + 1] + test::random_between(rng, -0.05, 0.05) * dx;
  }

  time_kernel("kernel only (P = F)", IdentityStress{}, cloud, y, fam, geo, state, false);
  time_kernel("Saint Venant-Kirchhoff 2D", test::SaintVenantKirchhoff2D{}, cloud, y, fam, geo, state, false);
#ifdef BENCH_HAVE_GENT
  MaterialParameters p;
  p.mu = 4.55e3;
  p.Jm = 162.6;
  p.D  = 2.0 / (1000.0 * p.mu);
  time_kernel("Gent plane stress, warm c33", GentPlaneStress{p}, cloud, y, fam, geo, state, true);
  time_kernel("Gent plane stress, cold c33", GentPlaneStress{p}, cloud, y, fam, geo, state, false);
#endif

#ifdef BENCH_HAVE_GENT
  {
    // The model alone, on the F of every bond (warm c33 from a first pass): how much of
    // the kernel's time is the constitutive law.
    const GentPlaneStress gent{p};
    std::vector<Mat2>     Fs;
    for (std::size_t i = 0; i < cloud.size(); i += 7)
      for (std::size_t q = 0; q < fam.size(i); ++q) Fs.push_back(bond_deformation_gradient(cloud, y.data(), fam, geo, state, i, q));
    std::vector<double> c(Fs.size(), 0.0);
    Mat2                P;
    for (std::size_t k = 0; k < Fs.size(); ++k) gent.stress(Fs[k], c[k], P);
    for (int warm = 1; warm >= 0; --warm) {
      double best = 1e300, sink = 0;
      for (int r = 0; r < 10; ++r) {
        const auto a = std::chrono::steady_clock::now();
        for (std::size_t k = 0; k < Fs.size(); ++k) {
          double cc = warm ? c[k] : 0.0;
          gent.stress(Fs[k], cc, P);
          sink += P[0];
        }
        best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count());
      }
      std::printf("%-34s %7.2f ns/call (%s c33)%s\n", "GentPlaneStress::stress alone", 1e9 * best / static_cast<double>(Fs.size()),
                  warm ? "warm" : "cold", sink == 12345.0 ? "!" : "");
    }
  }
#endif

  {
    std::vector<double> t(2 * fam.n_bonds(), 1.0), f(2 * cloud.size());
    double              best = 1e300;
    for (int r = 0; r < 20; ++r) {
      const auto a = std::chrono::steady_clock::now();
      assemble_force_density(fam, cloud, t.data(), cloud.size(), f.data());
      best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count());
    }
    std::printf("%-34s %7.2f ns/bond\n", "assemble_force_density", 1e9 * best / nb);
  }

  // Memory: every per-point and per-bond array of the force evaluation.
  const double W = static_cast<double>(fam.mask_words);
  struct Item {
    const char *name;
    double      bytes;
  } items[] = {
      {"cloud x, volume, family_volume, natural_id", np * (16 + 8 + 8 + 8)},
      {"current positions y", np * 16},
      {"force density f", np * 16},
      {"families offsets", np * 8},
      {"families neighbour (int32)", nb * 4},
      {"families reverse (int32)", nb * 4},
      {"families BA masks", nb * 8 * W},
      {"bond state intact masks", np * 8 * W},
      {"geometry usable + singular masks", np * 16 * W},
      {"bond forces t_ij", nb * 16},
      {"c33 warm start (optional)", nb * 8},
  };
  double total = 0;
  for (const Item &it : items) {
    std::printf("  %-44s %7.1f B/point\n", it.name, it.bytes / np);
    total += it.bytes;
  }
  std::printf("  %-44s %7.1f B/point (%.1f without c33)\n", "total", total / np, (total - nb * 8) / np);
  return 0;
}
