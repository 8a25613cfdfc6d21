// 3D force-kernel benchmark: bond evaluations per second per core of the
// dimension-generic BA core (ba_force.hpp) in D = 3 with the compressible Gent law
// (Gent3D) on a simple cubic box, and the bytes per point of its arrays.
//
//   kernel_bench_3d [--side N] [--factor f] [--reps r] [--table]
//
//   --side N    N^3 lattice points (default 41: LAMMPS' `-var n 40` lattice, so that
//               bench/kernel_bench_3d.sh times both on the very same bonds)
//   --factor f  horizon delta = f dx (default 3.015)
//   --reps r    timed repetitions per measurement, the minimum is reported (default 5)
//   --table     also print one machine-readable line, `RESULT key=value ...`
//   --only NAME time that measurement alone (bond_only corrected energy lanes_bond_only
//               lanes_corrected lanes_energy identity assemble; the others print 0): for
//               perf record and for alternating A/B runs
//
// What is measured (thread CPU time, minimum over reps; absolute times on a shared
// machine mean little: compare ratios from one run, bench/kernel_bench_3d.sh):
//   bond_only      compute_bond_forces, the paper's form (eq 23), no correction
//   corrected      the same with the tensor stress correction (g -> M_i^{-1} g)
//   energy         the energy-consistent form (ba_force.hpp's, in 3D)
//   lanes_*        the same three with the lane path of the law (Compressible3DLanes,
//                  compressible_lanes.hpp: lane_count bonds at a time, no libm cbrt)
//   identity       the bond-only kernel with P = F: gather, masked sums, K^{-1}, F,
//                  stores, no constitutive cost
//   assemble       assemble_force_density, f_i = sum_j (t_ij - t_ji) V_j
// "bond" = one intact bond with a usable K handed to the model; a force evaluation is
// kernel + assemble.
//
// Build: the `kernel_bench_3d` target (bench/CMakeLists.txt).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <random>
#include <string>
#include <vector>

#include "bapd/core/materials/gent.hpp"
#include "bapd/core/materials/material.hpp"
#include "bapd/core/kernel/ba_force.hpp"
#include "bapd/core/materials/compressible_lanes.hpp"
#include "bapd/core/geometry/family.hpp"

using namespace bapd;

namespace {

struct IdentityStress { // P = F: the kernel's own work
  StressStatus stress(const nd::Mat<3> &F, nd::Mat<3> &P) const
  {
    P = F;
    return StressStatus::ok;
  }
};

double thread_seconds()
{
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

template <class Body> double time_min(int reps, Body &&body)
{
  double best = 1e300;
  for (int r = 0; r < reps; ++r) {
    const double t0 = thread_seconds();
    body(r);
    best = std::min(best, thread_seconds() - t0);
  }
  return best;
}

} // namespace

int main(int argc, char **argv)
{
  int    side = 41, reps = 5;
  double factor = 3.015;
  bool   table  = false;
  std::string only;
  for (int a = 1; a < argc; ++a) {
    const std::string s = argv[a];
    if (s == "--table") table = true;
    else if (a + 1 < argc && s == "--side") side = std::atoi(argv[++a]);
    else if (a + 1 < argc && s == "--factor") factor = std::atof(argv[++a]);
    else if (a + 1 < argc && s == "--reps") reps = std::max(1, std::atoi(argv[++a]));
    else if (a + 1 < argc && s == "--only") only = argv[++a];
    else {
      std::fprintf(stderr, "kernel_bench_3d: bad argument %s (see the top of bench/kernel_bench_3d.cpp)\n", s.c_str());
      return 2;
    }
  }
  const double dx    = 5e-4;
  PointCloud   cloud = nd::box_lattice<3>({side, side, side}, dx);
  const double s0    = thread_seconds();
  const Families fam = nd::build_families<3>(cloud, cloud.size(), factor * dx);
  compute_family_volumes(cloud, fam);
  const BondState     state(fam);
  nd::BondGeometry<3> geo, corrected;
  nd::compute_bond_geometry<3>(cloud, fam, state, geo);
  corrected.stress_correction = StressCorrection::tensor;
  nd::compute_bond_geometry<3>(cloud, fam, state, corrected);
  const double setup = thread_seconds() - s0;
  const double np = static_cast<double>(cloud.size()), nb = static_cast<double>(fam.n_bonds());
  std::printf("%d^3 lattice, delta = %.3f dx: %zu points, %zu bonds (%.2f per point), mask words %zu; setup %.2f s CPU\n",
              side, factor, cloud.size(), fam.n_bonds(), nb / np, fam.mask_words, setup);

  // Stretch 1.2 / 0.9 / 1.1 with 5 % dx noise; two states 1e-5 dx apart alternate.
  std::mt19937                           rng(1);
  std::uniform_real_distribution<double> noise(-1.0, 1.0);
  std::vector<double>                    ya(cloud.x.size()), yb(cloud.x.size());
  const double                           stretch[3] = {1.2, 0.9, 1.1};
  for (std::size_t k = 0; k < ya.size(); ++k) {
    ya[k] = stretch[k % 3] * cloud.x[k] + 0.05 * dx * noise(rng);
    yb[k] = ya[k] + 1e-5 * dx * noise(rng);
  }
  const double *ys[2] = {ya.data(), yb.data()};

  MaterialParameters p; // the paper's hydrogel (examples/*.yaml)
  p.D = 2.0 / (1000.0 * p.mu);
  const Gent3D                        gent{p};
  const nd::Compressible3DLanes<Gent> gent_lanes{ParametersOf<Gent>(p)};

  std::vector<double> t(3 * fam.n_bonds()), f(3 * cloud.size());
  nd::Workspace<3>    ws;
  const KernelStats   stats = nd::compute_bond_forces<3>(ForceForm::bond_only, gent, cloud, ys[0], fam, geo, state,
                                                         nullptr, t.data(), ws);
  if (!stats.ok()) std::printf("warning: %zu bonds failed in the model\n", stats.failed());
  const double evaluated = static_cast<double>(stats.evaluated);
  auto         run       = [&](ForceForm form, const auto &model, const nd::BondGeometry<3> &g) {
    return [&, form](int r) {
      nd::compute_bond_forces<3>(form, model, cloud, ys[r % 2], fam, g, state, nullptr, t.data(), ws);
    };
  };
  auto timed = [&](const char *name, auto &&body) { return only.empty() || only == name ? time_min(reps, body) : 0.0; };
  const IdentityStress identity;
  const double bond_only = timed("bond_only", run(ForceForm::bond_only, gent, geo));
  const double corr      = timed("corrected", run(ForceForm::bond_only, gent, corrected));
  const double energy    = timed("energy", run(ForceForm::energy_consistent, gent, geo));
  const double lanes_bo  = timed("lanes_bond_only", run(ForceForm::bond_only, gent_lanes, geo));
  const double lanes_co  = timed("lanes_corrected", run(ForceForm::bond_only, gent_lanes, corrected));
  const double lanes_ec  = timed("lanes_energy", run(ForceForm::energy_consistent, gent_lanes, geo));
  const double ident     = timed("identity", run(ForceForm::bond_only, identity, geo));
  const double assemble  = timed("assemble", [&](int) {
    nd::assemble_force_density<3>(fam, cloud, t.data(), cloud.size(), f.data());
  });

  auto line = [&](const char *name, double cpu, double count) {
    std::printf("  %-44s %8.2f ns/bond  %7.2f M bonds/s\n", name, 1e9 * cpu / count, count / cpu / 1e6);
  };
  std::printf("minimum of %d repetitions, thread CPU time:\n", reps);
  line("Gent3D bond-only (kernel)", bond_only, evaluated);
  line("Gent3D bond-only, tensor correction (kernel)", corr, evaluated);
  line("Gent3D energy-consistent (kernel)", energy, evaluated);
  line("Gent3D lanes bond-only (kernel)", lanes_bo, evaluated);
  line("Gent3D lanes bond-only, tensor correction", lanes_co, evaluated);
  line("Gent3D lanes energy-consistent (kernel)", lanes_ec, evaluated);
  line("kernel only (P = F)", ident, evaluated);
  line("assemble_force_density", assemble, nb);
  line("force evaluation, bond-only + assembly", bond_only + assemble, evaluated);
  line("force evaluation, energy-consistent + assembly", energy + assemble, evaluated);
  line("force evaluation, lanes bond-only + assembly", lanes_bo + assemble, evaluated);
  line("force evaluation, lanes energy-consistent + assembly", lanes_ec + assemble, evaluated);

  // Memory: every per-point and per-bond array of a 3D force evaluation (no c33: 3D
  // needs no plane-stress solve). Per point: x, y, f (3 doubles each), volume,
  // family_volume, natural_id, CSR offset, intact / usable / singular masks, C_i.
  const double W = static_cast<double>(fam.mask_words);
  const double per_point = 24 + 24 + 24 + 8 + 8 + 8 + 8 + 8 * W + 16 * W + 72;
  // Per bond: neighbour and reverse (int32), the BA mask, t_ij (3 doubles).
  const double per_bond = 4 + 4 + 8 * W + 24;
  const double bytes    = per_point + per_bond * nb / np;
  std::printf("  arrays: %.0f B/point (%.0f per point + %.0f per bond x %.1f bonds)\n", bytes, per_point, per_bond, nb / np);
  if (table)
    std::printf("RESULT side=%d factor=%.3f points=%zu bonds=%zu evaluated=%zu mask_words=%zu bond_only_ns=%.3f "
                "corrected_ns=%.3f energy_ns=%.3f lanes_bond_only_ns=%.3f lanes_corrected_ns=%.3f lanes_energy_ns=%.3f "
                "identity_ns=%.3f assemble_ns=%.3f bytes_per_point=%.0f\n",
                side, factor, cloud.size(), fam.n_bonds(), stats.evaluated, fam.mask_words, 1e9 * bond_only / evaluated,
                1e9 * corr / evaluated, 1e9 * energy / evaluated, 1e9 * lanes_bo / evaluated,
                1e9 * lanes_co / evaluated, 1e9 * lanes_ec / evaluated, 1e9 * ident / evaluated, 1e9 * assemble / nb, bytes);
  return 0;
}
