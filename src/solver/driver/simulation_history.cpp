// What a run reports: history.csv, static states, progress lines, the summary and
// the layout-independent final state.
#include "bapd/solver/driver/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <limits>
#include <sys/stat.h>
#include <unistd.h>

#include "bapd/core/kernel/damage.hpp"
#include "bapd/solver/io/fields.hpp"
#include "bapd/solver/io/output_directory.hpp"
#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/parallel/reproducible_sum.hpp"

namespace bapd {

namespace {

// Concatenates every rank's values on rank 0, in rank order (callers sort or index
// them by natural id, so the order does not matter).
template <class T> PetscErrorCode GatherOnRankZero(MPI_Comm comm, const std::vector<T> &mine, MPI_Datatype type, std::vector<T> *all)
{
  PetscMPIInt rank, size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  std::vector<int> counts(size), displs(size, 0);
  int              m = (int)mine.size();
  PetscCallMPI(MPI_Gather(&m, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm));
  all->clear();
  if (rank == 0) {
    for (int r = 1; r < size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
    all->resize(displs[size - 1] + counts[size - 1]);
  }
  PetscCallMPI(MPI_Gatherv(mine.data(), m, type, all->data(), counts.data(), displs.data(), type, 0, comm));
  PetscFunctionReturn(0);
}

} // namespace


// A fresh run's history.csv, with its header and the row at t = 0 (a restart's is
// written from its checkpoint's rows by HistoryReport::Restore).
template <int D> PetscErrorCode SimulationD<D>::OpenHistory()
{
  PetscFunctionBegin;
  if (!output_.checkpoint.restart.empty()) PetscFunctionReturn(0);
  PetscCall(history_.Open(comm_));
  PetscCall(WriteHistoryRow(0, 0.0));
  PetscFunctionReturn(0);
}

// Kinetic and internal energy, reproducible sums; no allocation (scratch sized at set-up).
template <int D> PetscErrorCode SimulationD<D>::Energies(double *kinetic, double *internal, Vec state)
{
  const PetscInt n = layout_.n_owned;
  const double  *x;

  PetscFunctionBegin;
  if (!state) state = X_;
  PetscCall(VecGetArrayRead(state, &x));
  PetscCall(force_.PointEnergies(x, point_energy_.data()));
  const double *v = x + D * n;
  for (PetscInt i = 0; i < n; ++i) {
    const double m     = scene_.material.density * layout_.cloud.volume[i];
    per_point_[2 * i]     = PointKineticEnergy<D>(m, v + D * i); // 1/2 m v.v (relaxation.hpp)
    per_point_[2 * i + 1] = point_energy_[i];
  }
  PetscCall(VecRestoreArrayRead(state, &x));
  double sums[2];
  PetscCall(ReproducibleSum(comm_, 2, n, per_point_.data(), sums));
  *kinetic  = sums[0];
  *internal = sums[1];
  PetscFunctionReturn(0);
}

// The displacement of every probe's point, on every rank (D per probe).
template <int D> PetscErrorCode SimulationD<D>::ReadProbes(const double *u_owned, double *probe_u)
{
  PetscFunctionBegin;
  for (std::size_t p = 0; p < probes_.size(); ++p) {
    if (probes_[p].owner_rank == rank_)
      for (int c = 0; c < D; ++c) probe_u[D * p + c] = u_owned[D * probes_[p].local_index + c];
    PetscCallMPI(MPI_Bcast(&probe_u[D * p], D, MPI_DOUBLE, probes_[p].owner_rank, comm_));
  }
  PetscFunctionReturn(0);
}

// The mean displacement of each load set's points (D per set), a reproducible sum
// over the set's points divided by their count: the same bits on any rank layout. For
// a rigid grip it is the displacement the grip imposes. No allocation.
template <int D> PetscErrorCode SimulationD<D>::GripDisplacements(const double *u_owned, double *mean)
{
  PetscFunctionBegin;
  const std::vector<LoadSetPoints> &sets = loading_.load_set_points();
  for (std::size_t s = 0; s < sets.size(); ++s) {
    const std::vector<PetscInt> &points = sets[s].points;
    for (std::size_t k = 0; k < points.size(); ++k)
      for (int c = 0; c < D; ++c) grip_terms_[D * k + c] = u_owned[D * points[k] + c];
    PetscCall(ReproducibleSum(comm_, D, (PetscInt)points.size(), grip_terms_.data(), &mean[D * s]));
    for (int c = 0; c < D; ++c) mean[D * s + c] /= (double)sets[s].global_count;
  }
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::BrokenBondCount(PetscInt *count)
{
  PetscFunctionBegin;
  PetscInt local = (PetscInt)bond_state_.count_broken(families_, (std::size_t)layout_.n_owned);
  PetscCallMPI(MPI_Allreduce(&local, count, 1, MPIU_INT, MPI_SUM, comm_));
  *count /= 2; // each broken bond is seen from both of its end points
  PetscFunctionReturn(0);
}

// One row of history.csv; keeps the values for the static-hold test. No allocation.
template <int D> PetscErrorCode SimulationD<D>::WriteHistoryRow(PetscInt step, double t, bool checks)
{
  const double *x;

  PetscFunctionBegin;
  PetscCall(PetscLogStagePush(stage_output_));
  PetscCall(VecGetArrayRead(X_, &x));
  PetscCall(ComputeForceDensity(x, force_density_.data()));
  PetscCall(loading_.Reactions(force_density_.data(), last_reaction_.data()));
  PetscCall(ReadProbes(x, last_probe_u_.data()));
  PetscCall(GripDisplacements(x, grip_u_.data()));
  PetscCall(VecRestoreArrayRead(X_, &x));
  PetscCall(Energies(&last_kinetic_, &last_internal_));
  PetscInt broken;
  PetscCall(BrokenBondCount(&broken));
  double crack_area = 0, crack_tip[4] = {0, 0, 0, 0};
  if (scene_.failure.enabled) PetscCall(CrackExtent(&crack_area, crack_tip));
  // Every rank holds the same sums (reproducible), so every rank decides alike.
  const double work     = budget_.grip_work_total();
  const double residual = work - (last_internal_ + last_kinetic_ + budget_.damped() + budget_.released());
  if (checks) PetscCall(WarnEnergyBalance(step, t, work, residual)); // (its cadence the -output_interval rows')
  HistoryRow row;
  row.step         = step;
  row.time         = t;
  row.stretch      = loading_.stretch_at(t);
  row.reaction     = last_reaction_.data();
  row.probe_u      = last_probe_u_.data();
  row.kinetic      = last_kinetic_;
  row.internal     = last_internal_;
  row.broken_bonds = broken;
  row.next_dt      = step_control_.current();
  row.budget       = &budget_;
  row.residual     = residual;
  row.crack_area   = crack_area;
  row.crack_tip    = crack_tip;
  row.grip_u       = grip_u_.data();
  PetscCall(history_.WriteRow(comm_, row));
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(0);
}

// An energy balance off by more than 1 % of the grips' work means that the dynamics made
// energy (or lost it) that no term accounts for: an explicit step too long for the
// stiffest bonds, typically those ahead of a running crack, whose one point then flies
// off (docs/validation.md 3.3). Said once, when it first happens, with the fix. Only for
// the energy-consistent force: the bond-only force is not a gradient, so its residual
// has another cause.
template <int D> PetscErrorCode SimulationD<D>::WarnEnergyBalance(PetscInt step, double t, double work, double residual)
{
  PetscFunctionBegin;
  if (warned_balance_ || scene_.material.force_form != ForceForm::energy_consistent) PetscFunctionReturn(0);
  if (!(work > 0) || !(std::fabs(residual) > 0.01 * work)) PetscFunctionReturn(0);
  warned_balance_ = true;
  // Held by the travel limit far below the stiffness step, the step is not the cause
  // and a lower safety would change nothing (docs/validation.md 3.3).
  const TimeStepControl &c      = step_control_;
  const bool             flying = c.current() < 0.5 * c.stiffness_step();
  const std::string      cause =
    flying ? Format(", while points fly and the travel limit holds the step at %.3g x the stiffness step: the step is not the cause and "
                    "-time_step_safety will not help; what follows the onset is not a converged result (docs/validation.md 3.3)",
                    c.current() / c.stiffness_step())
           : std::string(": the explicit step is too long for the stiffest bonds (a crack tip, a point thrown off); lower "
                         "-time_step_safety (0.2 keeps the notched sheet's crack within 0.01 %)");
  PetscCall(PetscFPrintf(comm_, PETSC_STDERR,
                         "bapd: warning: at step %" PetscInt_FMT " (stretch %.4f) the energy balance is off by %.2g %% of the grips' work "
                         "(energy_balance_residual_J in history.csv)%s\n",
                         step, loading_.stretch_at(t), 100 * std::fabs(residual) / work, cause.c_str()));
  PetscFunctionReturn(0);
}

// Ends a hold of the load schedule once the body is static (kinetic energy below
// -static_tolerance times the internal energy, at a history row): records the static
// state in static_states.csv and moves the rest of the schedule earlier, so that the
// next ramp starts now. Every input to the test is a reproducible sum, so the same
// steps end the same holds on any number of ranks.
template <int D> PetscErrorCode SimulationD<D>::CheckStaticHold(PetscInt step, double t)
{
  PetscFunctionBegin;
  if (scene_.time_stepping.static_tolerance <= 0) PetscFunctionReturn(0);
  const PetscInt k = loading_.HoldAt(t); // a hold that has not ended yet, or -1
  if (k < 0 || !(last_kinetic_ < scene_.time_stepping.static_tolerance * last_internal_)) PetscFunctionReturn(0);
  const double lambda = loading_.stretch_at(t);
  PetscCall(PetscPrintf(comm_, "Static at stretch %.5f: t = %.6e s, step %" PetscInt_FMT ", kinetic/internal energy %.3e < %.3e", lambda, t, step,
                        last_kinetic_ / last_internal_, scene_.time_stepping.static_tolerance));
  for (std::size_t p = 0; p < probes_.size(); ++p)
    PetscCall(PetscPrintf(comm_, "; %s ux = %.6e m", scene_.loading.probes[p].name.c_str(), last_probe_u_[D * p]));
  if (relaxation_.active()) PetscCall(PetscPrintf(comm_, "; damping %.4g 1/s", relaxation_.last()));
  PetscCall(PetscPrintf(comm_, "\n"));
  PetscCall(history_.WriteStaticState(comm_, lambda, t, step, last_kinetic_ / last_internal_, last_probe_u_.data(), last_reaction_.data()));
  // Skip what is left of the hold.
  loading_.EndHold(k, t);
  PetscCall(TSSetMaxTime(ts_, loading_.end_time()));
  PetscFunctionReturn(0);
}

// One progress line (ProgressObserver, simulation_report.cpp, decides when): step, time,
// step size, stretch, energies, broken bonds, wall time (since the start) and the wall
// time left. Collective (the energies are sums); prints only.
template <int D> PetscErrorCode SimulationD<D>::ProgressLine(PetscInt step, double t, double wall)
{
  PetscFunctionBegin;
  const double end_time = loading_.end_time();
  if (scene_.failure.enabled) PetscCall(BrokenBondCount(&total_broken_));
  double kinetic, internal;
  PetscCall(Energies(&kinetic, &internal));
  const double left     = t > 0 ? std::max(0.0, wall * (end_time - t) / t) : 0.0;
  char shortened[64] = "";
  // Why the step is short: points flying (the travel limit) or a stiffer material.
  const double dt = step_control_.current(), base = step_control_.base();
  if (dt < base)
    PetscCall(PetscSNPrintf(shortened, sizeof shortened, " (%.3g x, %s)", dt / base, dt < step_control_.stiffness_step() ? "fast points" : "stiffer"));
  PetscCall(PetscPrintf(comm_, "step %8" PetscInt_FMT "  t %.4e s  dt %.3e s%s  stretch %.4f  KE %.3e J  IE %.3e J  broken %" PetscInt_FMT "  wall %.1f s  left ~%.1f s\n",
                        step, t, dt, shortened, loading_.stretch_at(t), kinetic, internal, total_broken_, wall, left));
  PetscFunctionReturn(0);
}

// How the step went (time_step_control.hpp): how many steps were shortened, and why,
// and what re-estimating the stable step cost.
template <int D> PetscErrorCode SimulationD<D>::TimeStepSummary(PetscInt steps)
{
  const TimeStepControl &c = step_control_;

  PetscFunctionBegin;
  if (c.reestimating() && c.estimates() > 0)
    PetscCall(PetscPrintf(comm_, "time step: re-estimated %" PetscInt_FMT " time(s) (%" PetscInt_FMT " force evaluations, %.1f s); lambda_max up to %.3g x its value at rest\n",
                          c.estimates(), c.estimate_evaluations(), c.estimate_seconds(), c.largest_lambda() / c.lambda_rest()));
  if (c.tip_searches() > 0) // TimeStepControl::CrackTipSearch: the steps that broke bonds
    PetscCall(PetscPrintf(comm_, "time step: %" PetscInt_FMT " crack-tip search(es) after steps that broke bonds, %" PetscInt_FMT " of them shortened the step\n",
                          c.tip_searches(), c.tip_shortenings()));
  if (c.kinks() > 0) // TimeStepControl::Kink: a bond at a switch, read from both sides
    PetscCall(PetscPrintf(comm_, "time step: %" PetscInt_FMT " estimate(s) dropped: a kink of the force (a bond switching its state), not a stiffness\n", c.kinks()));
  if (c.shortened_steps() > 0) {
    char travel[96] = "";
    if (c.shortened_by_travel() > 0)
      PetscCall(PetscSNPrintf(travel, sizeof travel, ", %" PetscInt_FMT " by the travel limit (%.3g dx%s, fast points)", c.shortened_by_travel(),
                              c.travel() / scene_.body.dx(), c.travel_automatic() ? ", chosen with failure" : ""));
    PetscCall(PetscPrintf(comm_, "time step: %" PetscInt_FMT " of %" PetscInt_FMT " step(s) shorter than the full %.4e s: %" PetscInt_FMT " by stiffness (the material stiffened)%s; the shortest %.4e s = %.3g x\n",
                          c.shortened_steps(), steps, c.base(), c.shortened_by_stiffness(), travel, c.shortest(), c.shortest() / c.base()));
  }
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::Summary()
{
  PetscInt  step;
  PetscReal t;

  PetscFunctionBegin;
  PetscCall(TSGetStepNumber(ts_, &step));
  PetscCall(TSGetTime(ts_, &t));
  const double *x;
  std::vector<double> probe_u(D * probes_.size(), 0.0), reaction(D * scene_.loading.sets.size(), 0.0);
  PetscCall(VecGetArrayRead(X_, &x));
  PetscCall(ReadProbes(x, probe_u.data()));
  PetscCall(ComputeForceDensity(x, force_density_.data()));
  PetscCall(loading_.Reactions(force_density_.data(), reaction.data()));
  PetscCall(VecRestoreArrayRead(X_, &x));
  PetscCall(PetscPrintf(comm_, "\n%s: %" PetscInt_FMT " steps, t = %.6e s, stretch %.5f, wall %.1f s\n",
                        stopped_on_error_ ? "Stopped (see the error below)" : "Finished", step, t, loading_.stretch_at(t),
                        MPI_Wtime() - wall_start_));
  for (std::size_t p = 0; p < probes_.size(); ++p)
    if (D == 2)
      PetscCall(PetscPrintf(comm_, "probe %-16s ux = %+.6e m  uy = %+.6e m\n", scene_.loading.probes[p].name.c_str(), probe_u[2 * p], probe_u[2 * p + 1]));
    else
      PetscCall(PetscPrintf(comm_, "probe %-16s ux = %+.6e m  uy = %+.6e m  uz = %+.6e m\n", scene_.loading.probes[p].name.c_str(), probe_u[D * p],
                            probe_u[D * p + 1], probe_u[D * p + 2]));
  for (std::size_t s = 0; s < scene_.loading.sets.size(); ++s)
    if (D == 2)
      PetscCall(PetscPrintf(comm_, "load set %-12s reaction y = %+.6e N  nominal stress = %+.6e Pa\n", scene_.loading.sets[s].name.c_str(),
                            reaction[D * s + 1], reaction[D * s + 1] / NominalArea(BodyExtentOf(scene_))));
    else
      PetscCall(PetscPrintf(comm_, "load set %-12s reaction x, y, z = %+.6e, %+.6e, %+.6e N  nominal stress (y) = %+.6e Pa\n",
                            scene_.loading.sets[s].name.c_str(), reaction[D * s], reaction[D * s + 1], reaction[D * s + 2],
                            reaction[D * s + 1] / NominalArea(BodyExtentOf(scene_))));
  PetscInt broken;
  PetscCall(BrokenBondCount(&broken));
  if (scene_.failure.enabled) PetscCall(PetscPrintf(comm_, "broken bonds: %" PetscInt_FMT "\n", broken));
  if (!stopped_on_error_) { // (a diverged run's state is the last good one, its budget the step that failed)
    double kinetic, internal;
    PetscCall(Energies(&kinetic, &internal));
    const double work = budget_.grip_work_total(), residual = work - (internal + kinetic + budget_.damped() + budget_.released());
    PetscCall(PetscPrintf(comm_,
                          "energy: the grips' work %.4e J = internal %.4e + kinetic %.4e + damping %.4e + fracture %.4e J, residual "
                          "%.2g %% of the work\n",
                          work, internal, kinetic, budget_.damped(), budget_.released(), work > 0 ? 100 * residual / work : 0.0));
    if (scene_.failure.enabled) {
      double area, tip[4];
      PetscCall(CrackExtent(&area, tip));
      if (area > 0)
        PetscCall(PetscPrintf(comm_, "crack: area %.4e m^2, effective toughness %.4g J/m^2 (fracture / area), reach %.4e m\n", area,
                              budget_.released() / area, tip[0]));
    }
  }
  PetscCall(TimeStepSummary(step));
  if (relaxation_.active())
    PetscCall(PetscPrintf(comm_, "adaptive relaxation: damping %.4g 1/s now, %.4g to %.4g 1/s over the run\n", relaxation_.last(),
                          relaxation_.smallest(), relaxation_.largest()));
  PetscCall(ListOutputFiles());
  PetscFunctionReturn(0);
}

namespace {

std::string Size(std::uintmax_t bytes)
{
  char text[32];
  if (bytes < 1000) std::snprintf(text, sizeof text, "%ju B", bytes);
  else if (bytes < 1000000) std::snprintf(text, sizeof text, "%.1f kB", bytes / 1e3);
  else if (bytes < 1000000000) std::snprintf(text, sizeof text, "%.1f MB", bytes / 1e6);
  else std::snprintf(text, sizeof text, "%.2f GB", bytes / 1e9);
  return text;
}

} // namespace

// The end of the summary: every file this run wrote (or extended, after a restart),
// with its size, so that nothing written goes unnoticed and nothing missing is named.
template <int D> PetscErrorCode SimulationD<D>::ListOutputFiles()
{
  PetscFunctionBegin;
  if (rank_ != 0) PetscFunctionReturn(0);
  const std::string dir = paths_.dir() + "/"; // (as the summary prints it)
  std::string       text;
  std::uintmax_t    total = 0;
  auto line = [&](const std::string &name, const std::string &what) {
    std::error_code      ec;
    const std::uintmax_t bytes = std::filesystem::file_size(paths_.file(name), ec);
    if (ec) return; // not written (or gone: the run's own checks say so)
    total += bytes;
    text += Format("  %-22s %10s  %s\n", name.c_str(), Size(bytes).c_str(), what.c_str());
  };
  line("history.csv", "a row every -output_interval steps and at each end time / -output_history_rows (scripts/plot_history.py)");
  if (history_.has_static_states()) line("static_states.csv", "one row per static state");
  if (output_.fields.enabled) {
    std::uintmax_t bytes = 0;
    std::size_t    files = 0;
    for (const FieldFrame &frame : output_.series.frames) {
      std::error_code      ec;
      const std::uintmax_t b = std::filesystem::file_size(paths_.field_file(frame.step), ec);
      if (!ec) bytes += b, ++files;
    }
    total += bytes;
    line("fields.xdmf", "open in ParaView");
    text += Format("  %-22s %10s  %zu field file(s), t = %.4g to %.4g s\n", "fields/", Size(bytes).c_str(), files,
                   output_.series.frames.empty() ? 0.0 : output_.series.frames.front().time,
                   output_.series.frames.empty() ? 0.0 : output_.series.frames.back().time);
  }
  if (output_.last_checkpoint_step >= 0)
    line("checkpoint.h5", Format("step %" PetscInt_FMT ": continue with -restart %s", output_.last_checkpoint_step, paths_.checkpoint().c_str()));
  if (scene_.output.final_state) {
    line("final_state.csv", "every point's displacement, natural order");
    line("broken_bonds.csv", "broken bonds as pairs of natural ids");
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "Output in %s (%s):\n%s", dir.c_str(), Size(total).c_str(), text.c_str()));
  PetscFunctionReturn(0);
}

// final_state.csv (natural id, reference position, displacement) and
// broken_bonds.csv (directed pairs of natural ids), in natural order: files that do
// not depend on the rank layout, for comparisons across runs.
template <int D> PetscErrorCode SimulationD<D>::WriteFinalState()
{
  std::vector<double>                      u, reference;
  std::vector<std::pair<int64_t, int64_t>> broken;

  PetscFunctionBegin;
  PetscCall(GatherDisplacement(&u));
  PetscCall(GatherNatural(layout_.cloud.x.data(), &reference)); // the layout's copies of the lattice positions
  PetscCall(GatherBrokenBonds(&broken));
  // [errno, which file failed (0 final_state.csv, 1 broken_bonds.csv)]: rank 0 writes, every rank learns it.
  // Each file whole or not at all (WriteFileWhole: a temporary name, renamed once
  // complete): a full disk leaves no torn last row.
  int error[2] = {0, 0};
  if (rank_ == 0) {
    error[0] = WriteFileWhole(paths_.final_state(), [&](FILE *f) {
      std::fprintf(f, D == 2 ? "natural_id,x_m,y_m,ux_m,uy_m\n" : "natural_id,x_m,y_m,z_m,ux_m,uy_m,uz_m\n");
      for (std::size_t i = 0; i < (std::size_t)layout_.n_global; ++i) {
        std::fprintf(f, "%zu", i);
        for (const std::vector<double> *values : {&reference, &u})
          for (int c = 0; c < D; ++c) std::fprintf(f, ",%.17g", (*values)[D * i + c]);
        std::fprintf(f, "\n");
      }
    });
    if (!error[0]) {
      error[1] = 1;
      error[0] = WriteFileWhole(paths_.broken_bonds(), [&](FILE *f) {
        std::fprintf(f, "i,j\n");
        for (const auto &b : broken) std::fprintf(f, "%lld,%lld\n", (long long)b.first, (long long)b.second);
      });
    }
  }
  PetscCallMPI(MPI_Bcast(error, 2, MPI_INT, 0, comm_));
  PetscCheck(!error[0], comm_, PETSC_ERR_FILE_WRITE,
             "Cannot write %s/%s: %s; it is not written (no partial file is left; a previous one stays as it was): free some space or "
             "choose another -output_dir",
             scene_.output.dir.c_str(), error[1] ? "broken_bonds.csv" : "final_state.csv", std::strerror(error[0]));
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::GatherDisplacement(std::vector<double> *u_natural)
{
  const double *x;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(X_, &x));
  const PetscErrorCode ierr = GatherNatural(x, u_natural);
  PetscCall(VecRestoreArrayRead(X_, &x));
  PetscCall(ierr);
  PetscFunctionReturn(0);
}

// D values per owned point, gathered on rank 0 in natural order (D per point).
template <int D> PetscErrorCode SimulationD<D>::GatherNatural(const double *values, std::vector<double> *natural)
{
  const PetscInt n = layout_.n_owned;

  PetscFunctionBegin;
  std::vector<double> mine((D + 1) * n); // the natural id, then the values
  for (PetscInt i = 0; i < n; ++i) {
    mine[(D + 1) * i] = (double)layout_.cloud.natural_id[i];
    for (int c = 0; c < D; ++c) mine[(D + 1) * i + 1 + c] = values[D * i + c];
  }
  std::vector<double> all;
  PetscCall(GatherOnRankZero(comm_, mine, MPI_DOUBLE, &all));
  natural->clear();
  if (rank_ == 0) {
    natural->assign(D * layout_.n_global, 0.0);
    for (std::size_t k = 0; k < all.size(); k += D + 1) {
      const std::size_t id = (std::size_t)all[k];
      for (int c = 0; c < D; ++c) (*natural)[D * id + c] = all[k + 1 + c];
    }
  }
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::GatherBrokenBonds(std::vector<std::pair<int64_t, int64_t>> *bonds)
{
  PetscFunctionBegin;
  std::vector<long long> mine;
  for (PetscInt i = 0; i < layout_.n_owned; ++i)
    for (std::size_t b = families_.offsets[i]; b < families_.offsets[i + 1]; ++b)
      if (!bond_state_.is_intact((std::size_t)i, (std::size_t)(b - families_.offsets[i]))) {
        mine.push_back(layout_.cloud.natural_id[i]);
        mine.push_back(layout_.cloud.natural_id[families_.neighbour[b]]);
      }
  std::vector<long long> all;
  PetscCall(GatherOnRankZero(comm_, mine, MPI_LONG_LONG, &all));
  bonds->clear();
  for (std::size_t k = 0; k + 1 < all.size(); k += 2) bonds->push_back({all[k], all[k + 1]});
  std::sort(bonds->begin(), bonds->end());
  PetscFunctionReturn(0);
}

// The driver at D = 2 and 3 (main.cpp chooses one from the scene): the members defined
// here, one by one. simulation.cpp instantiates the class, which covers only what it
// defines; a class may be explicitly instantiated once in a program.
#define BAPD_SIMULATION_HISTORY(D) \
  template PetscErrorCode SimulationD<D>::OpenHistory(); \
  template PetscErrorCode SimulationD<D>::WarnEnergyBalance(PetscInt step, double t, double work, double residual); \
  template PetscErrorCode SimulationD<D>::Energies(double *kinetic, double *internal, Vec state); \
  template PetscErrorCode SimulationD<D>::ReadProbes(const double *u_owned, double *probe_u); \
  template PetscErrorCode SimulationD<D>::BrokenBondCount(PetscInt *count); \
  template PetscErrorCode SimulationD<D>::GripDisplacements(const double *u_owned, double *mean); \
  template PetscErrorCode SimulationD<D>::WriteHistoryRow(PetscInt step, double t, bool checks); \
  template PetscErrorCode SimulationD<D>::CheckStaticHold(PetscInt step, double t); \
  template PetscErrorCode SimulationD<D>::ProgressLine(PetscInt step, double t, double wall); \
  template PetscErrorCode SimulationD<D>::TimeStepSummary(PetscInt steps); \
  template PetscErrorCode SimulationD<D>::Summary(); \
  template PetscErrorCode SimulationD<D>::ListOutputFiles(); \
  template PetscErrorCode SimulationD<D>::WriteFinalState(); \
  template PetscErrorCode SimulationD<D>::GatherDisplacement(std::vector<double> *u_natural); \
  template PetscErrorCode SimulationD<D>::GatherNatural(const double *values, std::vector<double> *natural); \
  template PetscErrorCode SimulationD<D>::GatherBrokenBonds(std::vector<std::pair<int64_t, int64_t>> *bonds);
BAPD_SIMULATION_HISTORY(2)
BAPD_SIMULATION_HISTORY(3)
#undef BAPD_SIMULATION_HISTORY

} // namespace bapd
