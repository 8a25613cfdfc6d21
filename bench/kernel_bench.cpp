// Force-kernel benchmark: bond evaluations per second per core
// of the BA kernel (nd::compute_bond_forces<2>, ba_force.hpp) with the Gent plane-stress
// model on a square lattice, and the pieces it is made of.
//
//   kernel_bench [--side N] [--factor f] [--reps r] [--callgrind] [--table]
//
//   --side N      N x N lattice points (default 300; 100, 316, 1000 give 1e4, 1e5, 1e6)
//   --factor f    horizon delta = f dx (default 3.015)
//   --reps r      timed repetitions per measurement, the minimum is reported (default 10)
//   --callgrind   run every measured region once, between CALLGRIND_TOGGLE_COLLECT
//                 markers, and dump one profile per region (CALLGRIND_DUMP_STATS_AT):
//                 run under `valgrind --tool=callgrind --collect-atstart=no`
//                 (`bench/run_all.sh --only callgrind` does this with the kernel_profile
//                 build and reads the profiles)
//   --table       also print one machine-readable line, `RESULT key=value ...`
//   --only NAME   run only the region NAME (gent_warm, energy_warm, gent_dynamics,
//                 identity, energy_identity, model_lanes, assemble), reps times, and print its time: for a sampling
//                 profiler (`perf record -e cpu-clock kernel_bench --only energy_warm
//                 --reps 200`; docs/notes/performance-kernel-2.md 1c)
// Per bond against LAMMPS peri/lps in the same run: bench/kernel_bench_lammps.sh.
//
// What is measured (every time is the minimum over reps of the thread CPU time, which
// a busy shared machine disturbs much less than wall clock; the minimum wall time is
// printed beside it):
//   gent_warm   the kernel as the solver calls it each step: Gent plane stress, c33
//               warm-started from the previous evaluation at a slightly different y
//               (the positions alternate between two states 1e-5 dx apart, about one
//               time step's motion), so the S33 = 0 Newton solve starts near its root
//   gent_cold   the same without warm start (c33 = 0: starts from 1/J~^2)
//   gent_dynamics  as gent_warm with the two states 5e-4 dx apart (--dynamics-motion):
//               a time step's motion in the solver, where F moves by up to ~1e-3 (up to
//               commit ea828f1 the solve then needed 1.75 residual evaluations per bond,
//               as in the solver's time loop, 1.71; since the fourth-order warm step,
//               1.00 here and 1.05-1.14 in the solver; --dynamics-motion 1e-3: 1.08)
//   identity    the kernel with P = F: gather, masked sums, K^{-1}, F, force vector
//               and stores, no constitutive cost
//   energy_identity  the energy-consistent form with P = F: what that form costs
//               whatever the model (docs/notes/performance-kernel-3.md 1l)
//   model       GentPlaneStress::stress alone on every bond's F (warm c33): the scalar
//               solve, one bond at a time (the bond kernel runs stress_lanes)
//   model_lanes the same on the lanes (stress_lanes, lane_count bonds a call, every
//               batch full and independent): the model's cost in the kernel at best
//   assemble    assemble_force_density, f_i = sum_j (t_ij - t_ji) V_j
//   energy_warm the energy-consistent form (ForceForm::energy_consistent) as gent_warm:
//               the energy-consistent form, assembled by the same assemble_force_density
//   incompressible, energy_incompressible  gent_warm and energy_warm with Gent in
//               incompressible plane stress (plane_stress_incompressible.hpp: C33 =
//               1/J~^2, no solve), and incompressible_lanes its stress_lanes alone;
//               the ratio to the compressible solve is printed beside them
// "bond evaluation" = one intact bond with a usable K handed to the model (eq 23),
// KernelStats::evaluated; a full force evaluation is gent_warm + assemble.
//
// Build: the `kernel_bench` target (bench/CMakeLists.txt), or standalone from the
// repository root once CMake has configured build/ (it writes the law headers' list,
// build/generated/core):
//   g++ -std=c++17 -O3 -march=native -DNDEBUG -ffp-contract=off -Iinclude -Ibuild/generated/core
//       bench/kernel_bench.cpp src/core/*/*.cpp -o /tmp/kernel_bench
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <functional>
#include <utility>
#include <random>
#include <string>
#include <vector>

#include "bapd/core/geometry/family.hpp"
#include "bapd/core/kernel/ba_force.hpp"
#include "bapd/core/materials/gent.hpp"
#include "bapd/core/materials/material.hpp"
#include "bapd/core/materials/plane_stress_incompressible.hpp"
#include "bapd/core/geometry/lattice.hpp"

#if defined(BAPD_BENCH_CALLGRIND) && __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define BENCH_HAVE_CALLGRIND 1
#else
#define CALLGRIND_TOGGLE_COLLECT
#define CALLGRIND_DUMP_STATS_AT(name) (void)(name)
#endif

using namespace bapd;

namespace {

// P = F: no constitutive cost, measures the kernel's own work. On the lanes, as every
// 2D model runs (model_lanes: collecting the bonds, the form's products in lanes);
// one bond at a time it took 12.2-12.6 ns a bond for bond-only at 3.015 dx
// (docs/notes/performance-kernel-3.md 1i).
struct IdentityStress {
  static constexpr bool has_lanes = true;
  StressStatus          stress(const Mat2 &F, double &, Mat2 &P) const
  {
    P = F;
    return StressStatus::ok;
  }
  template <class T> MaskOf<T> stress_lanes(const std::array<T, 4> &F, T &, std::array<T, 4> &P) const
  {
    P = F;
    return T{} == T{}; // every lane done
  }
};

double thread_seconds()
{
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double wall_seconds() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

struct Timing {
  double cpu = 1e300, wall = 1e300; // minimum over the repetitions
};

// Runs body() reps times and keeps the minimum CPU and wall time.
template <class Body> Timing time_min(int reps, Body &&body)
{
  Timing t;
  for (int r = 0; r < reps; ++r) {
    const double c0 = thread_seconds(), w0 = wall_seconds();
    body(r);
    const double c1 = thread_seconds(), w1 = wall_seconds();
    t.cpu  = std::min(t.cpu, c1 - c0);
    t.wall = std::min(t.wall, w1 - w0);
  }
  return t;
}

// In --callgrind mode: one run of body() with collection on, dumped as `name`.
template <class Body> void profile_region(const char *name, Body &&body)
{
  CALLGRIND_TOGGLE_COLLECT;
  body(0);
  CALLGRIND_TOGGLE_COLLECT;
  CALLGRIND_DUMP_STATS_AT(name);
}

// Effective core clock: a chain of dependent integer adds retires one add per cycle
// on every x86 core since the Pentium 4, so cycles = adds and f = adds / CPU time.
double measure_clock_ghz()
{
  const long n    = 400000000;
  double     best = 1e300;
  for (int r = 0; r < 5; ++r) {
    long         x  = 0;
    const double t0 = thread_seconds();
    for (long k = 0; k < n; k += 8) {
      // 8 dependent adds per iteration; the asm keeps the compiler from folding them
      asm volatile("add $1, %0\n\tadd $1, %0\n\tadd $1, %0\n\tadd $1, %0\n\t"
                   "add $1, %0\n\tadd $1, %0\n\tadd $1, %0\n\tadd $1, %0"
                   : "+r"(x));
    }
    best = std::min(best, thread_seconds() - t0);
    if (x != n) std::abort();
  }
  return static_cast<double>(n) / best / 1e9;
}

struct Options {
  int    side      = 300;
  double factor    = 3.015;
  int    reps      = 10;
  bool   callgrind = false;
  bool   table     = false;
  bool   clock     = false;
  double motion    = 1e-5; // dx: how far the two position states are apart (one time step's motion)
  double dynamics  = 5e-4; // dx: the same for gent_dynamics
  std::string only;        // --only: one region
};

Options parse(int argc, char **argv)
{
  Options o;
  for (int a = 1; a < argc; ++a) {
    const std::string s    = argv[a];
    auto              next = [&]() -> const char * {
      if (a + 1 >= argc) {
        std::fprintf(stderr, "kernel_bench: %s needs a value\n", s.c_str());
        std::exit(2);
      }
      return argv[++a];
    };
    if (s == "--side") o.side = std::atoi(next());
    else if (s == "--factor") o.factor = std::atof(next());
    else if (s == "--reps") o.reps = std::max(1, std::atoi(next()));
    else if (s == "--callgrind") o.callgrind = true;
    else if (s == "--table") o.table = true;
    else if (s == "--clock") o.clock = true;
    else if (s == "--motion") o.motion = std::atof(next());
    else if (s == "--dynamics-motion") o.dynamics = std::atof(next());
    else if (s == "--only") o.only = next();
    else {
      std::fprintf(stderr, "kernel_bench: unknown argument %s (see the comment at the top of bench/kernel_bench.cpp)\n",
                   s.c_str());
      std::exit(2);
    }
  }
  return o;
}

} // namespace

int main(int argc, char **argv)
{
  const Options o = parse(argc, argv);
  if (o.clock) { // only the clock probe (bench/run_all.sh uses it for the peak estimate)
    std::printf("RESULT clock_ghz=%.3f\n", measure_clock_ghz());
    return 0;
  }
#ifndef BENCH_HAVE_CALLGRIND
  if (o.callgrind) {
    std::fprintf(stderr, "kernel_bench: built without callgrind markers; use the kernel_profile target\n");
    return 2;
  }
#endif
  const double dx = 1e-3;
  Body<2>       body;
  body.width = body.height = o.side * dx;
  body.thickness           = 1e-3;
  body.dx                  = dx;

  const double   s0    = wall_seconds();
  PointCloud     cloud = make_lattice(body);
  const Families fam   = build_families(cloud, cloud.size(), o.factor * dx, body.notches);
  compute_family_volumes(cloud, fam);
  const BondState state(fam);
  nd::BondGeometry<2>    geo;
  nd::compute_bond_geometry<2>(cloud, fam, state, geo);
  const double setup = wall_seconds() - s0;
  const double np = static_cast<double>(cloud.size()), nb = static_cast<double>(fam.n_bonds());
  std::printf("%d x %d lattice, delta = %.3f dx: %zu points, %zu bonds (%.2f per point), mask words %zu; setup %.2f s\n",
              o.side, o.side, o.factor, cloud.size(), fam.n_bonds(), nb / np, fam.mask_words, setup);

  // A moderately large, non-affine deformation: stretch 1.5 x 0.8 plus 5 % dx noise;
  // y_b is y_a moved by --motion (1e-5) dx at random: a small time step's motion.
  std::mt19937                           rng(1);
  std::uniform_real_distribution<double> noise(-1.0, 1.0);
  std::vector<double>                    y_a(cloud.x.size()), y_b(cloud.x.size()), y_c(cloud.x.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    y_a[2 * i]     = 1.5 * cloud.x[2 * i] + 0.05 * dx * noise(rng);
    y_a[2 * i + 1] = 0.8 * cloud.x[2 * i + 1] + 0.05 * dx * noise(rng);
    y_b[2 * i]     = y_a[2 * i] + o.motion * dx * noise(rng);
    y_b[2 * i + 1] = y_a[2 * i + 1] + o.motion * dx * noise(rng);
  }
  // gent_dynamics: the states are 5e-4 dx apart, about a time step's motion in the
  // solver (up to ea828f1 this needed as many residual evaluations as the solver's time
  // loop, 1.75 against 1.71; now 1.00 here, 1.08 at 1e-3 dx, 1.32 at 2e-3 dx).
  for (std::size_t k = 0; k < y_c.size(); ++k) y_c[k] = y_a[k] + o.dynamics * dx * noise(rng);
  const double *ys[2] = {y_a.data(), y_b.data()}, *ys_dyn[2] = {y_a.data(), y_c.data()};

  MaterialParameters p; // the paper's hydrogel (examples/*.yaml)
  p.mu = 4.55e3;
  p["-material_Jm"] = 162.6;
  p.D  = 2.0 / (1000.0 * p.mu);
  const GentPlaneStress gent{p};
  const PlaneStressIncompressible<Gent> gel{p}; // the same gel at J = 1 exactly

  std::vector<double> c33(fam.n_bonds(), 0.0), t(2 * fam.n_bonds()), f(2 * cloud.size());
  nd::Workspace<2> ws;
  KernelStats         stats = nd::compute_bond_forces<2>(ForceForm::bond_only, gent, cloud, ys[1], fam, geo, state, c33.data(), t.data(), ws);
  const double        evaluated = static_cast<double>(stats.evaluated);
  if (!stats.ok()) std::printf("warning: %zu bonds failed in the model\n", stats.failed());

  // The model alone, on the F of every bond, for both position states.
  std::vector<Mat2>   Fs[2];
  std::vector<double> c_model;
  for (int s = 0; s < 2; ++s) {
    Fs[s].reserve(fam.n_bonds());
    for (std::size_t i = 0; i < cloud.size(); ++i)
      for (std::size_t q = 0; q < fam.size(i); ++q)
        if (geo.is_usable(i, q)) Fs[s].push_back(nd::bond_deformation_gradient<2>(cloud, ys[s], fam, geo, state, i, q));
  }
  c_model.assign(Fs[0].size(), 0.0);
  {
    Mat2 P;
    for (std::size_t k = 0; k < Fs[1].size(); ++k) gent.stress(Fs[1][k], c_model[k], P);
  }
  // Mean residual evaluations (one cbrt each) per bond, warm and cold.
  double evals_warm = 0, evals_cold = 0;
  for (std::size_t k = 0; k < Fs[0].size(); ++k) {
    evals_warm += gent.solve(Fs[0][k], c_model[k]).evaluations;
    evals_cold += gent.solve(Fs[0][k], 0.0).evaluations;
  }
  evals_warm /= static_cast<double>(Fs[0].size());
  double evals_dyn = 0;
  {
    std::vector<double> c(Fs[0].size(), 0.0);
    std::size_t         k = 0;
    Mat2                P;
    for (std::size_t i = 0; i < cloud.size(); ++i)
      for (std::size_t q = 0; q < fam.size(i); ++q)
        if (geo.is_usable(i, q)) gent.stress(nd::bond_deformation_gradient<2>(cloud, y_c.data(), fam, geo, state, i, q), c[k++], P);
    for (k = 0; k < Fs[0].size(); ++k) evals_dyn += gent.solve(Fs[0][k], c[k]).evaluations;
    evals_dyn /= static_cast<double>(Fs[0].size());
  }
  evals_cold /= static_cast<double>(Fs[0].size());

  double sink     = 0;
  auto   gent_run = [&](int r) {
    nd::compute_bond_forces<2>(ForceForm::bond_only, gent, cloud, ys[r % 2], fam, geo, state, c33.data(), t.data(), ws);
  };
  std::vector<double> c33_dyn(fam.n_bonds(), 0.0);
  nd::compute_bond_forces<2>(ForceForm::bond_only, gent, cloud, ys_dyn[1], fam, geo, state, c33_dyn.data(), t.data(), ws);
  auto dynamics_run = [&](int r) {
    nd::compute_bond_forces<2>(ForceForm::bond_only, gent, cloud, ys_dyn[r % 2], fam, geo, state, c33_dyn.data(), t.data(), ws);
  };
  std::vector<double> c33_energy(c33); // its own warm start, from the same state
  auto                energy_run = [&](int r) {
    nd::compute_bond_forces<2>(ForceForm::energy_consistent, gent, cloud, ys[r % 2], fam, geo, state, c33_energy.data(), t.data(), ws);
  };
  auto cold_run = [&](int r) {
    nd::compute_bond_forces<2>(ForceForm::bond_only, gent, cloud, ys[r % 2], fam, geo, state, nullptr, t.data(), ws);
  };
  auto identity_run = [&](int r) {
    nd::compute_bond_forces<2>(ForceForm::bond_only, IdentityStress{}, cloud, ys[r % 2], fam, geo, state, nullptr, t.data(), ws);
  };
  auto energy_identity_run = [&](int r) {
    nd::compute_bond_forces<2>(ForceForm::energy_consistent, IdentityStress{}, cloud, ys[r % 2], fam, geo, state, nullptr, t.data(), ws);
  };
  auto model_run = [&](int r) {
    const std::vector<Mat2> &F = Fs[r % 2];
    Mat2                     P;
    for (std::size_t k = 0; k < F.size(); ++k) {
      gent.stress(F[k], c_model[k], P);
      sink += P[0];
    }
  };
  // The model alone on the lanes (stress_lanes, lane_count bonds a call), every batch
  // independent and full: what the model costs the kernel at best.
  std::vector<std::array<Lanes, 4>> F_lanes[2];
  std::vector<Lanes>                c_lanes((Fs[0].size() + lane_count - 1) / lane_count, Lanes{});
  for (int s = 0; s < 2; ++s) {
    F_lanes[s].assign(c_lanes.size(), {Lanes{} + 1.0, Lanes{}, Lanes{}, Lanes{} + 1.0});
    for (std::size_t k = 0; k < Fs[s].size(); ++k)
      for (int comp = 0; comp < 4; ++comp) F_lanes[s][k / lane_count][comp][k % lane_count] = Fs[s][k][comp];
  }
  for (std::size_t k = 0; k < Fs[0].size(); ++k) c_lanes[k / lane_count][k % lane_count] = c_model[k];
  auto model_lanes_run = [&](int r) {
    const std::vector<std::array<Lanes, 4>> &F = F_lanes[r % 2];
    std::array<Lanes, 4>                     P;
    for (std::size_t b = 0; b < F.size(); ++b) {
      gent.stress_lanes(F[b], c_lanes[b], P);
      sink += P[0][0];
    }
  };
  std::vector<double> c33_gel(fam.n_bonds(), 0.0); // written (1/J~^2), never read
  auto incompressible_run = [&](int r) {
    nd::compute_bond_forces<2>(ForceForm::bond_only, gel, cloud, ys[r % 2], fam, geo, state, c33_gel.data(), t.data(), ws);
  };
  auto energy_incompressible_run = [&](int r) {
    nd::compute_bond_forces<2>(ForceForm::energy_consistent, gel, cloud, ys[r % 2], fam, geo, state, c33_gel.data(), t.data(), ws);
  };
  auto incompressible_lanes_run = [&](int r) {
    const std::vector<std::array<Lanes, 4>> &F = F_lanes[r % 2];
    std::array<Lanes, 4>                     P;
    Lanes                                    c{};
    for (std::size_t b = 0; b < F.size(); ++b) {
      gel.stress_lanes(F[b], c, P);
      sink += P[0][0];
    }
  };
  auto assemble_run = [&](int) { nd::assemble_force_density<2>(fam, cloud, t.data(), cloud.size(), f.data()); };

  if (o.callgrind) {
    // Warm c33 is at y_b (last evaluation above); the profiled evaluation is at y_a.
    profile_region("gent_warm", gent_run);
    profile_region("assemble", assemble_run);
    profile_region("identity", identity_run);
    profile_region("model_warm", model_run);
    profile_region("gent_cold", cold_run);
    profile_region("gent_dynamics", dynamics_run); // c33 warm at y_c: evaluated at y_a
    profile_region("energy_warm", energy_run);     // c33_energy warm at y_b: evaluated at y_a
    std::printf("callgrind regions dumped: gent_warm assemble identity model_warm gent_cold gent_dynamics energy_warm (%zu "
                "bond evaluations "
                "each, %zu model calls)\n",
                stats.evaluated, Fs[0].size());
    std::printf("RESULT side=%d factor=%.3f points=%zu bonds=%zu evaluated=%zu model_calls=%zu evals_warm=%.4f "
                "evals_cold=%.4f\n",
                o.side, o.factor, cloud.size(), fam.n_bonds(), stats.evaluated, Fs[0].size(), evals_warm, evals_cold);
    return sink == 12345.0;
  }

  if (!o.only.empty()) {
    const std::pair<const char *, std::function<void(int)>> regions[] = {
        {"gent_warm", gent_run}, {"energy_warm", energy_run}, {"gent_dynamics", dynamics_run},
        {"identity", identity_run}, {"energy_identity", energy_identity_run}, {"model_lanes", model_lanes_run},
        {"assemble", assemble_run}, {"incompressible", incompressible_run}, {"energy_incompressible", energy_incompressible_run},
        {"incompressible_lanes", incompressible_lanes_run}};
    for (const auto &[name, run] : regions)
      if (o.only == name) {
        const Timing tm = time_min(o.reps, run);
        std::printf("%s: %.2f ns/bond (thread CPU, minimum of %d)\n", name, 1e9 * tm.cpu / evaluated, o.reps);
        return 0;
      }
    std::fprintf(stderr, "kernel_bench: --only %s: not a region (gent_warm energy_warm gent_dynamics identity energy_identity model_lanes assemble incompressible energy_incompressible incompressible_lanes)\n",
                 o.only.c_str());
    return 2;
  }
  const Timing gent_t            = time_min(o.reps, gent_run);
  const Timing cold_t            = time_min(std::max(1, o.reps / 2), cold_run);
  const Timing dyn_t             = time_min(o.reps, dynamics_run);
  const Timing energy_t          = time_min(o.reps, energy_run);
  const Timing identity_t        = time_min(o.reps, identity_run);
  const Timing energy_identity_t = time_min(o.reps, energy_identity_run);
  const Timing model_t           = time_min(o.reps, model_run);
  const Timing model_lanes_t     = time_min(o.reps, model_lanes_run);
  const Timing assemble_t        = time_min(o.reps, assemble_run);
  const Timing incompressible_t  = time_min(o.reps, incompressible_run);
  const Timing energy_inc_t      = time_min(o.reps, energy_incompressible_run);
  const Timing inc_lanes_t       = time_min(o.reps, incompressible_lanes_run);
  const double nm                = static_cast<double>(Fs[0].size());

  auto line = [&](const char *name, const Timing &tm, double count, const char *unit) {
    std::printf("  %-38s %8.2f ns/%s  %7.2f M/s  (wall: %8.2f ns)\n", name, 1e9 * tm.cpu / count, unit,
                count / tm.cpu / 1e6, 1e9 * tm.wall / count);
  };
  std::printf("minimum of %d repetitions, thread CPU time:\n", o.reps);
  line("Gent plane stress, warm c33 (kernel)", gent_t, evaluated, "bond");
  line("Gent plane stress, cold c33 (kernel)", cold_t, evaluated, "bond");
  line("Gent plane stress, dynamics (kernel)", dyn_t, evaluated, "bond");
  line("  energy-consistent, warm c33", energy_t, evaluated, "bond");
  line("kernel only (P = F)", identity_t, evaluated, "bond");
  line("  energy-consistent, P = F", energy_identity_t, evaluated, "bond");
  line("GentPlaneStress::stress alone, warm", model_t, nm, "call");
  line("  stress_lanes alone, warm", model_lanes_t, nm, "bond");
  line("assemble_force_density", assemble_t, nb, "bond");
  line("Gent incompressible plane stress (kernel)", incompressible_t, evaluated, "bond");
  line("  energy-consistent", energy_inc_t, evaluated, "bond");
  line("  stress_lanes alone", inc_lanes_t, nm, "bond");
  std::printf("  incompressible / compressible (warm): kernel %.3f, energy-consistent %.3f, stress_lanes %.3f\n",
              incompressible_t.cpu / gent_t.cpu, energy_inc_t.cpu / energy_t.cpu, inc_lanes_t.cpu / model_lanes_t.cpu);
  std::printf("  residual evaluations per bond: %.3f warm, %.3f dynamics, %.3f cold\n", evals_warm, evals_dyn, evals_cold);
  const double force_cpu = gent_t.cpu + assemble_t.cpu;
  std::printf("  full force evaluation (warm kernel + assembly): %.2f ns/bond, %.2f M bonds/s\n",
              1e9 * force_cpu / evaluated, evaluated / force_cpu / 1e6);

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
      {"c33 warm start", nb * 8},
  };
  double total = 0;
  for (const Item &it : items) total += it.bytes;
  std::printf("  kernel arrays: %.1f B/point\n", total / np);

  if (o.table)
    std::printf("RESULT side=%d factor=%.3f points=%zu bonds=%zu evaluated=%zu bonds_per_point=%.3f setup_s=%.3f "
                "gent_warm_ns=%.3f gent_cold_ns=%.3f identity_ns=%.3f model_ns=%.3f assemble_ns=%.3f "
                "gent_warm_wall_ns=%.3f evals_warm=%.4f evals_cold=%.4f kernel_bytes_per_point=%.1f energy_warm_ns=%.3f "
                "gent_dynamics_ns=%.3f evals_dynamics=%.4f energy_identity_ns=%.3f model_lanes_ns=%.3f "
                "incompressible_ns=%.3f energy_incompressible_ns=%.3f incompressible_lanes_ns=%.3f\n",
                o.side, o.factor, cloud.size(), fam.n_bonds(), stats.evaluated, nb / np, setup,
                1e9 * gent_t.cpu / evaluated, 1e9 * cold_t.cpu / evaluated, 1e9 * identity_t.cpu / evaluated,
                1e9 * model_t.cpu / nm, 1e9 * assemble_t.cpu / nb, 1e9 * gent_t.wall / evaluated, evals_warm,
                evals_cold, total / np, 1e9 * energy_t.cpu / evaluated, 1e9 * dyn_t.cpu / evaluated, evals_dyn,
                1e9 * energy_identity_t.cpu / evaluated, 1e9 * model_lanes_t.cpu / nm,
                1e9 * incompressible_t.cpu / evaluated, 1e9 * energy_inc_t.cpu / evaluated, 1e9 * inc_lanes_t.cpu / nm);
  return sink == 12345.0;
}
