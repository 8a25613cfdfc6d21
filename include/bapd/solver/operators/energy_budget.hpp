#pragma once
// The run's energy budget (docs/method.md section 5.3): the work each load set's grips
// have done, the kinetic energy damping has taken and the elastic energy breaking bonds
// have released, so that history.csv can show where the grips' work went:
//
//     W_grips = E_internal + E_kinetic + E_damping + E_released + residual.
//
// With the energy-consistent force (f = -dE/du) and velocity Verlet the residual is the
// integrator's O(dt^2) error; the bond-only force is not a gradient, so its residual
// also measures how far it is from one.
//
// Each step (TS pre-step to post-step):
// - a grip dof k of point i moves from u_k(start) to u_k(end) while the body pulls on it
//   with the force density f_k of the step's evaluations: the grip does the work
//   -mean(f_k) V_i (u_k(end) - u_k(start)) (the midpoint rule at velocity Verlet's one
//   evaluation a step), and ½ m (v_k(set)^2 - v_k^2) when it sets the dof's speed
//   again after the damping (and at t = 0, from rest);
// - mass-proportional damping v <- exp(-c dt) v takes ½ m (1 - exp(-2 c dt)) |v|^2 of
//   every point (the grips' share comes back with the speed they set);
// - a breaking pass releases E(before) - E(after), the internal energy at the same
//   positions with the bonds of before and after the pass (the caller evaluates both).
// The step's terms are summed over the ranks in one reproducible sum, so the totals
// (and every column) are the same bits on any number of ranks; a checkpoint keeps the
// totals, so a restart continues them bit for bit.
// The dimension D = 2 or 3 is a run-time value: nothing here runs per bond.
#include <petscsys.h>

#include <vector>

#include "bapd/solver/operators/loading.hpp"
#include "bapd/solver/parallel/layout.hpp"

namespace bapd {

class EnergyBudget {
public:
  // The grips of `loading` (set up), grouped by load set; `density` [kg/m^3] gives the
  // points' masses from their volumes. Local; allocates what the steps use.
  PetscErrorCode Setup(const Loading &loading, const Layout &layout, double density, std::size_t load_sets);
  // A fresh run, after the grips set their speeds at t = 0: the kinetic energy they
  // gave the body is their first work. Collective.
  PetscErrorCode Start(MPI_Comm comm, const double *v_owned);
  // The step's start (TS pre-step): the grips' positions; clears the force record.
  void BeginStep(const double *u_owned);
  // Every force evaluation of the dynamics in the step (owned force density, D a point,
  // before the grips' dofs are zeroed).
  void RecordForce(const double *force_density);
  // Before the damping's decay v <- decay v (owned velocities; decay 1 without damping),
  // every step: the energy it takes, and the grips' speeds before they set them again.
  void Damp(const double *v_owned, double decay);
  // After the grips set u and v at the step's end: the grips' work over the step, and
  // the step's terms added to the totals. Collective (one reproducible sum).
  PetscErrorCode EndStep(MPI_Comm comm, const double *u_owned, const double *v_owned);
  // A breaking pass released this internal energy (E before - E after, the caller's).
  void Release(double released) { released_ += released; }

  double              grip_work(std::size_t set) const { return work_[set]; }
  double              grip_work_total() const;
  double              damped() const { return damped_; }
  double              released() const { return released_; }
  std::size_t         load_sets() const { return work_.size(); }
  // Checkpoints: [damped, released, work of each set] (assigned: no allocation once sized).
  void                totals(std::vector<double> *out) const;
  void                RestoreTotals(const std::vector<double> &totals);

private:
  struct GripDof {
    PetscInt    dof;   // D i + c
    PetscInt    point; // i
    std::size_t set;
    double      mass;  // of point i
  };
  int                  D_   = 2;
  PetscInt             n_   = 0; // owned points
  const double        *volume_ = nullptr;
  double               density_ = 0;
  std::vector<GripDof> grips_;
  std::vector<double>  u_start_, force_sum_, v_damped_; // a grip dof each
  int                  evaluations_ = 0;               // in this step
  std::vector<double>  terms_;                         // (1 + sets) a point: damping, work of each set
  std::vector<double>  sums_;                          // 1 + sets: the step's sums (sized once)
  double               damped_ = 0, released_ = 0;
  std::vector<double>  work_;                          // a load set each
};

} // namespace bapd
