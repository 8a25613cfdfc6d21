// stability_spectrum: the eigenvalues of the linearised equations of motion of a
// small scene, for docs/stability.md. One rank.
//
//   u'' = a(u),  a = f(u) / rho on the free degrees of freedom (grips held),
//   A = -da/du, built column by column by central differences of the solver's own
//   force density (every model, force form and formulation), then LAPACK dgeev.
//
// What the eigenvalues lambda of A say (docs/stability.md, section 1):
//   - explicit step: velocity Verlet is stable for dt < 2 / sqrt(lambda_max);
//   - flutter: the bond-only force form (paper eq 23) has a non-symmetric A next to
//     free surfaces, so some lambda = a + ib are complex, and the undamped motion
//     e^{st}, s^2 = -lambda, grows at Re s ~ |b| / (2 sqrt a) whatever the step;
//   - mass-proportional damping c (s^2 + c s + lambda = 0) removes that growth iff
//     c > |b| / sqrt(a) (the roots cross the imaginary axis at s = -ib/c, a = b^2/c^2),
//     i.e. c > 2 x the growth rate;
//   - a real lambda < 0 is a static instability (buckling), which no damping cures.
//
// Modes (the scene is read from the options, as bapd reads it):
//   -spectrum_stretches l1,l2,...        run the scene and analyse the state at each
//                                         applied stretch (the run's own path).
//   -spectrum_broken_fractions p1,p2,... no run: the body at rest with a random
//                                         fraction p of its bonds broken (seeded),
//                                         both force forms.
//   -spectrum_dump_forces                 also write <output_dir>/forces.csv, the
//                                         force density of the (last) state.
// Writes <output_dir>/spectrum.csv (one row per state) and
// <output_dir>/eigenvalues_<label>.csv (every eigenvalue).
#include <petscsys.h>
// after petscsys.h, which it needs
#include <petscblaslapack.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "bapd/core/kernel/ba_force.hpp"
#include "bapd/core/kernel/bond_geometry.hpp"
#include "bapd/core/kernel/bond_state.hpp"
#include "bapd/solver/driver/errors.hpp"
#include "bapd/core/geometry/family.hpp"
#include "bapd/core/geometry/lattice.hpp"
#include "bapd/core/materials/models.hpp"
#include "bapd/solver/input/scene.hpp"
#include "bapd/solver/driver/simulation.hpp"

namespace {

using Forces = std::function<PetscErrorCode(const std::vector<double> &u, std::vector<double> &force_density)>;

struct Spectrum {
  std::vector<double> re, im;
  double              lambda_max_re = 0, abs_lambda_max = 0, min_re = 0;
  double              growth = 0;          // max Re s of the undamped motion, 1/s
  double              critical_damping = 0; // smallest c that damps every mode, 1/s
  double              mode_x = 0, mode_y = 0; // largest amplitude of the mode that sets it
  double              asymmetry = 0;        // max |A_rs - A_sr| / max |A_rs|
};

// A = -d(f / rho)/du on the free dofs, column-major, by central differences.
PetscErrorCode BuildOperator(const Forces &forces, const std::vector<double> &u, const std::vector<PetscInt> &free_dofs,
                             double rho, double h, std::vector<double> *A)
{
  const std::size_t   n = free_dofs.size();
  std::vector<double> up = u, fp, fm;

  PetscFunctionBegin;
  A->assign(n * n, 0.0);
  for (std::size_t s = 0; s < n; ++s) {
    const PetscInt d = free_dofs[s];
    up[d]            = u[d] + h;
    PetscCall(forces(up, fp));
    up[d] = u[d] - h;
    PetscCall(forces(up, fm));
    up[d] = u[d];
    for (std::size_t r = 0; r < n; ++r) (*A)[r + s * n] = -(fp[free_dofs[r]] - fm[free_dofs[r]]) / (2 * h * rho);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Analyse(std::vector<double> A, std::size_t n, const std::vector<PetscInt> &free_dofs, const double *x_ref,
                       Spectrum *out)
{
  PetscBLASInt        N, lwork, info;
  std::vector<double> vr(n * n), work;
  Spectrum           &sp = *out;

  PetscFunctionBegin;
  double size = 0, asym = 0;
  for (std::size_t r = 0; r < n; ++r)
    for (std::size_t s = 0; s < n; ++s) {
      size = std::max(size, std::abs(A[r + s * n]));
      asym = std::max(asym, std::abs(A[r + s * n] - A[s + r * n]));
    }
  sp.asymmetry = asym / size;
  PetscCall(PetscBLASIntCast((PetscInt)n, &N));
  sp.re.resize(n), sp.im.resize(n);
  double       query = 0, dummy = 0;
  PetscBLASInt one = 1, minus_one = -1;
  LAPACKgeev_("N", "V", &N, A.data(), &N, sp.re.data(), sp.im.data(), &dummy, &one, vr.data(), &N, &query, &minus_one, &info);
  lwork = (PetscBLASInt)query;
  work.resize((std::size_t)lwork);
  LAPACKgeev_("N", "V", &N, A.data(), &N, sp.re.data(), sp.im.data(), &dummy, &one, vr.data(), &N, work.data(), &lwork, &info);
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK dgeev failed (info %d)", (int)info);

  sp.lambda_max_re = -HUGE_VAL, sp.min_re = HUGE_VAL, sp.abs_lambda_max = 0;
  for (std::size_t k = 0; k < n; ++k) {
    sp.lambda_max_re  = std::max(sp.lambda_max_re, sp.re[k]);
    sp.min_re         = std::min(sp.min_re, sp.re[k]);
    sp.abs_lambda_max = std::max(sp.abs_lambda_max, std::hypot(sp.re[k], sp.im[k]));
  }
  // Rigid-body and detached-point modes have lambda = 0 up to the differencing error
  // (~1e-9 of the largest): they neither grow nor need damping.
  const double zero = 1e-8 * sp.abs_lambda_max;
  std::size_t  worst = n;
  for (std::size_t k = 0; k < n; ++k) {
    const std::complex<double> lambda(sp.re[k], sp.im[k]);
    if (std::abs(lambda) < zero) continue;
    const double growth = std::abs(std::sqrt(-lambda).real());
    double       c      = growth > 0 && sp.re[k] <= 0 ? HUGE_VAL : std::abs(sp.im[k]) / std::sqrt(sp.re[k]);
    if (growth > sp.growth) sp.growth = growth;
    if (worst == n || c > sp.critical_damping) sp.critical_damping = c, worst = k;
  }
  // Where the mode that needs the most damping lives (its largest amplitude).
  if (worst < n) {
    const std::size_t j = sp.im[worst] < 0 && worst > 0 ? worst - 1 : worst; // a pair stores (re, im) in columns j, j + 1
    double            best = -1;
    for (std::size_t r = 0; r < n; ++r) {
      const PetscInt d = free_dofs[r];
      double         a = vr[r + j * n] * vr[r + j * n];
      if (sp.im[worst] != 0 && j + 1 < n) a += vr[r + (j + 1) * n] * vr[r + (j + 1) * n];
      if (a > best) best = a, sp.mode_x = x_ref[2 * (d / 2)], sp.mode_y = x_ref[2 * (d / 2) + 1];
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode WriteState(FILE *summary, const std::string &dir, const std::string &label, double stretch, double fraction,
                          const char *form, std::size_t n, double solver_dt, PetscInt unusable, const Spectrum &sp)
{
  PetscFunctionBegin;
  std::fprintf(summary, "%s,%.6g,%.6g,%s,%zu,%" PetscInt_FMT ",%.10e,%.10e,%.10e,%.10e,%.10e,%.6e,%.6e,%.6e,%.6g,%.6g,%.3e\n", label.c_str(),
               stretch, fraction, form, n, unusable, sp.lambda_max_re, sp.abs_lambda_max, 2.0 / std::sqrt(sp.abs_lambda_max), solver_dt,
               sp.min_re, sp.growth, sp.critical_damping, sp.asymmetry, sp.mode_x, sp.mode_y, std::sqrt(sp.abs_lambda_max));
  std::fflush(summary);
  FILE *f = std::fopen((dir + "/eigenvalues_" + label + ".csv").c_str(), "w");
  PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s/eigenvalues_%s.csv", dir.c_str(), label.c_str());
  std::fprintf(f, "re_1_s2,im_1_s2\n");
  for (std::size_t k = 0; k < sp.re.size(); ++k) std::fprintf(f, "%.10e,%.10e\n", sp.re[k], sp.im[k]);
  std::fclose(f);
  PetscFunctionReturn(0);
}

// The scene's run, analysed at each listed stretch of its schedule.
PetscErrorCode AlongTheRun(const std::vector<double> &stretches, FILE *summary, const std::string &dir, bool dump_forces)
{
  bapd::Simulation sim(PETSC_COMM_SELF);
  PetscReal        dt;

  PetscFunctionBegin;
  PetscCall(sim.Setup());
  const bapd::Scene  &scene = sim.scene();
  const bapd::Layout &layout = sim.layout();
  const PetscInt      n_owned = layout.n_owned;
  std::vector<char>   held(2 * n_owned, 0);
  for (const bapd::LoadSet &set : scene.loading.sets) {
    std::vector<PetscInt> points;
    PetscCall(bapd::LoadSetSelect(bapd::BodyExtentOf(scene), set, layout.cloud.x.data(), n_owned, &points));
    for (PetscInt p : points) {
      if (set.x != bapd::ComponentLoad::free) held[2 * p] = 1;
      if (set.y != bapd::ComponentLoad::free) held[2 * p + 1] = 1;
    }
  }
  std::vector<PetscInt> free_dofs;
  for (PetscInt d = 0; d < 2 * n_owned; ++d)
    if (!held[d]) free_dofs.push_back(d);
  Forces forces = [&](const std::vector<double> &u, std::vector<double> &f) {
    f.resize(u.size());
    return sim.ComputeForceDensity(u.data(), f.data());
  };
  PetscCall(TSGetTimeStep(sim.ts(), &dt));
  const bapd::Schedule &s = scene.loading.schedule;
  for (double target : stretches) {
    // The first time the schedule reaches the stretch (linear between knots).
    double t_target = -1;
    for (std::size_t k = 1; k < s.time.size() && t_target < 0; ++k)
      if ((s.stretch[k - 1] - target) * (s.stretch[k] - target) <= 0 && s.stretch[k] != s.stretch[k - 1])
        t_target = s.time[k - 1] + (target - s.stretch[k - 1]) / (s.stretch[k] - s.stretch[k - 1]) * (s.time[k] - s.time[k - 1]);
    if (target == 1.0) t_target = 0;
    PetscCheck(t_target >= 0, PETSC_COMM_SELF, PETSC_ERR_USER, "-spectrum_stretches: the schedule never reaches stretch %g", target);
    PetscReal t;
    PetscCall(TSGetTime(sim.ts(), &t));
    const PetscInt steps = (PetscInt)std::ceil((t_target - t) / dt - 1e-9);
    if (steps > 0) {
      const PetscErrorCode ierr = sim.Advance(steps);
      if (ierr) {
        PetscCall(PetscPrintf(PETSC_COMM_SELF, "The run stopped before stretch %g: no further spectra.\n", target));
        break;
      }
    }
    PetscCall(TSGetTime(sim.ts(), &t));
    const double lambda = s.stretch_at(t);
    const double *x;
    PetscCall(VecGetArrayRead(sim.state(), &x));
    std::vector<double> u(x, x + 2 * n_owned);
    PetscCall(VecRestoreArrayRead(sim.state(), &x));
    if (dump_forces) { // the force density of the state, per point (diagnosis)
      std::vector<double> f;
      PetscCall(forces(u, f));
      FILE *out = std::fopen((dir + "/forces.csv").c_str(), "w");
      std::fprintf(out, "natural_id,x_m,y_m,ux_m,uy_m,fx_N_m3,fy_N_m3\n");
      for (PetscInt i = 0; i < n_owned; ++i)
        std::fprintf(out, "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", (long long)layout.cloud.natural_id[i], layout.cloud.x[2 * i],
                     layout.cloud.x[2 * i + 1], u[2 * i], u[2 * i + 1], f[2 * i], f[2 * i + 1]);
      std::fclose(out);
    }
    std::vector<double> A;
    PetscCall(BuildOperator(forces, u, free_dofs, scene.material.density, 1e-5 * scene.body.sheet.dx, &A));
    Spectrum sp;
    PetscCall(Analyse(A, free_dofs.size(), free_dofs, layout.cloud.x.data(), &sp));
    char label[64];
    std::snprintf(label, sizeof label, "stretch%.3g", target);
    const char *form = bapd::to_string(scene.material.force_form);
    PetscCall(WriteState(summary, dir, label, lambda, 0.0, form, free_dofs.size(), sim.stable_time_step(), 0, sp));
    PetscCall(PetscPrintf(PETSC_COMM_SELF,
                          "stretch %.4f: lambda_max %.4e 1/s^2 (stable step %.4e s; solver's estimate at rest %.4e s), "
                          "growth %.3g 1/s, damping needed %.3g 1/s, asymmetry %.2e, mode at (%.4g, %.4g) m\n",
                          lambda, sp.abs_lambda_max, 2 / std::sqrt(sp.abs_lambda_max), sim.stable_time_step(), sp.growth,
                          sp.critical_damping, sp.asymmetry, sp.mode_x, sp.mode_y));
  }
  PetscFunctionReturn(0);
}

// The body at rest with a random fraction of its bonds broken, both force forms.
PetscErrorCode BrokenBonds(const std::vector<double> &fractions, FILE *summary, const std::string &dir)
{
  bapd::Scene scene;

  PetscFunctionBegin;
  PetscCall(bapd::SceneFromOptions(PETSC_COMM_SELF, &scene));
  PetscCall(bapd::CheckUnusedOptions(PETSC_COMM_SELF));
  bapd::PointCloud cloud    = bapd::make_lattice(scene.body.sheet);
  bapd::Families   families = bapd::build_families(cloud, cloud.size(), scene.body.horizon(), scene.body.sheet.notches);
  bapd::compute_family_volumes(cloud, families);
  const std::size_t     n = cloud.size();
  std::vector<PetscInt> free_dofs(2 * n);
  for (std::size_t d = 0; d < 2 * n; ++d) free_dofs[d] = (PetscInt)d;
  for (double p : fractions) {
    bapd::BondState    state(families);
    bapd::nd::BondGeometry<2> geometry;
    std::mt19937       rng(12345);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    std::size_t        broken = 0;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t q = 0; q < families.size(i); ++q) {
        const std::size_t j = (std::size_t)families.neighbour[families.offsets[i] + q];
        if (j > i && uniform(rng) < p) broken += bapd::break_bond(families, state, i, q);
      }
    const PetscInt unusable = (PetscInt)bapd::nd::compute_bond_geometry<2>(cloud, families, state, geometry);
    const std::size_t total = families.n_bonds() / 2;
    for (int form = 0; form < 2; ++form) {
      std::vector<double>    A;
      bapd::nd::Workspace<2> ws;
      std::vector<double>    bond_force(2 * families.n_bonds());
      Forces                 forces = [&](const std::vector<double> &u, std::vector<double> &f) {
        std::vector<double> y(cloud.x);
        for (std::size_t k = 0; k < y.size(); ++k) y[k] += u[k];
        bapd::with_model(scene.material.model, scene.material.formulation, scene.material.parameters, [&](const auto &model) {
          bapd::nd::compute_bond_forces<2>(form == 1 ? bapd::ForceForm::energy_consistent : bapd::ForceForm::bond_only, model,
                                           cloud, y.data(), families, geometry, state, nullptr, bond_force.data(), ws);
        });
        f.assign(2 * n, 0.0);
        bapd::nd::assemble_force_density<2>(families, cloud, bond_force.data(), n, f.data());
        return PetscErrorCode(0);
      };
      PetscCall(BuildOperator(forces, std::vector<double>(2 * n, 0.0), free_dofs, scene.material.density, 1e-5 * scene.body.sheet.dx, &A));
      Spectrum sp;
      PetscCall(Analyse(A, free_dofs.size(), free_dofs, cloud.x.data(), &sp));
      const char *name = form ? "energy_consistent" : "bond_only";
      char        label[96];
      std::snprintf(label, sizeof label, "broken%.2f_%s", p, name);
      PetscCall(WriteState(summary, dir, label, 1.0, (double)broken / total, name, free_dofs.size(), 0.0, unusable, sp));
      PetscCall(PetscPrintf(PETSC_COMM_SELF,
                            "%s, %.1f %% of %zu bonds broken (%" PetscInt_FMT " directed bonds with a singular K): lambda_max %.4e 1/s^2 "
                            "(stable step %.4e s), growth %.3g 1/s, damping needed %.3g 1/s, asymmetry %.2e\n",
                            name, 100.0 * broken / total, total, unusable, sp.abs_lambda_max, 2 / std::sqrt(sp.abs_lambda_max),
                            sp.growth, sp.critical_damping, sp.asymmetry));
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Main()
{
  PetscReal   stretches[64], fractions[64];
  PetscInt    n_stretches = 64, n_fractions = 64;
  PetscBool   have_stretches = PETSC_FALSE, have_fractions = PETSC_FALSE;
  PetscMPIInt size;
  char        dir[PETSC_MAX_PATH_LEN] = "output";

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCheck(size == 1, PETSC_COMM_WORLD, PETSC_ERR_USER, "stability_spectrum runs on one rank");
  PetscCall(PetscOptionsGetRealArray(nullptr, nullptr, "-spectrum_stretches", stretches, &n_stretches, &have_stretches));
  PetscCall(PetscOptionsGetRealArray(nullptr, nullptr, "-spectrum_broken_fractions", fractions, &n_fractions, &have_fractions));
  PetscCheck(have_stretches != have_fractions, PETSC_COMM_WORLD, PETSC_ERR_USER,
             "give one of -spectrum_stretches l1,l2,... or -spectrum_broken_fractions p1,p2,...");
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-output_dir", dir, sizeof dir, nullptr));
  std::filesystem::create_directories(dir);
  FILE *summary = std::fopen((std::string(dir) + "/spectrum.csv").c_str(), "w");
  PetscCheck(summary, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s/spectrum.csv", dir);
  std::fprintf(summary, "label,stretch,broken_fraction,force_form,free_dofs,singular_bonds,lambda_max_re_1_s2,abs_lambda_max_1_s2,"
                        "stable_dt_s,solver_rest_stable_dt_s,min_re_lambda_1_s2,growth_rate_1_s,critical_damping_1_s,asymmetry,mode_x_m,"
                        "mode_y_m,omega_max_1_s\n");
  PetscBool dump_forces = PETSC_FALSE;
  PetscCall(PetscOptionsGetBool(nullptr, nullptr, "-spectrum_dump_forces", &dump_forces, nullptr));
  PetscErrorCode ierr = have_stretches ? AlongTheRun(std::vector<double>(stretches, stretches + n_stretches), summary, dir, dump_forces)
                                       : BrokenBonds(std::vector<double>(fractions, fractions + n_fractions), summary, dir);
  std::fclose(summary);
  PetscCall(ierr);
  PetscFunctionReturn(0);
}

} // namespace

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  PetscCall(bapd::PushUserErrorHandler());
  const int code = bapd::FinishRun(Main());
  PetscCall(PetscFinalize());
  return code;
}
