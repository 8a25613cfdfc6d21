#pragma once
// The force operator: displacement of the owned points in, force density out
// (paper eq 23, or the energy-consistent form; ba_force.hpp at D = 2 or 3). It owns what
// an evaluation needs and nothing else: the ghosted displacement (two rings of
// ghosts, layout.hpp), the current positions y = x + u of every local point, the
// plane-stress warm starts C33 (one per bond), the bond forces t_ij, the kernel's
// workspace and the model, chosen once at set-up (models are chosen at run time
// once, outside the hot loop). The dimension D is chosen there too
// (Setup<D>): the closures hold the nd::<D> kernel and its workspace, and the rest
// (the exchange, y = x + u) is D values a point, a run-time D like Loading's. A 3D
// model has no C33: a 3D operator holds no warm starts (warm_start() is empty). The
// body (layout, families, geometry, bond state) is the caller's: bonds break between
// evaluations (failure.hpp).
//
// An evaluation changes nothing a later one reads unless asked: Evaluate(...,
// WarmStart::keep) leaves C33, the statistics and the failed-bond list as they were,
// so looking at a state (a history row, a field file, a test) never changes the
// dynamics (the converged C33 depends on its start at the round-off level). Only the
// dynamics commits.
#include <petscvec.h>

#include <functional>
#include <vector>

#include "bapd/core/kernel/bond_state.hpp"
#include "bapd/core/geometry/family.hpp"
#include "bapd/solver/parallel/layout.hpp"
#include "bapd/core/kernel/ba_force.hpp"
#include "bapd/solver/input/scene.hpp"

namespace bapd {

class ForceOperator {
public:
  enum class WarmStart { keep, commit };

  ForceOperator() = default;
  ~ForceOperator() { VecDestroy(&u_ghosted_); }
  int dimension() const { return dimension_; } // D, set by Setup<D>
  ForceOperator(const ForceOperator &)            = delete;
  ForceOperator &operator=(const ForceOperator &) = delete;

  // stage_ghost and stage_force: the -log_view stages of the exchange and the bond loop.
  // D = 2: the scene's 2D formulation (with_model); D = 3: the law's 3D form (with_model_3d).
  template <int D>
  PetscErrorCode Setup(MPI_Comm comm, const MaterialSection &force, const Layout &layout, const Families &families,
                       const nd::BondGeometry<D> &geometry, const BondState &state, PetscLogStage stage_ghost,
                       PetscLogStage stage_force);

  // y = x + u over every local point, after the ghost exchange of u (owned, D per point).
  PetscErrorCode UpdatePositions(const double *u_owned);
  // Force density (D per owned point) for u_owned. commit: the dynamics' evaluation,
  // which advances the warm starts, the statistics and the list of failed bonds.
  PetscErrorCode Evaluate(const double *u_owned, double *force_density, WarmStart warm_start);
  // With a warm start the caller owns (advanced in place, 1 per bond): a probe of the
  // operator, e.g. the stable-step estimate, that leaves the operator's state as it was.
  PetscErrorCode EvaluateWithWarmStart(const double *u_owned, double *force_density, std::vector<double> &c33);
  // With warm starts that are only read (1 per bond; the operator's own, warm_start(),
  // or the caller's): a probe that needs no copy of them (8 B a bond). Leaves the
  // operator's state and c33 as they were.
  PetscErrorCode EvaluateFrom(const double *u_owned, double *force_density, const std::vector<double> &c33);
  // V_i W_i of the owned points at u_owned (strain_energy, ba_force.hpp).
  PetscErrorCode PointEnergies(const double *u_owned, double *energy);
  // Psi(F_ij) of every bond of the family points (owned and ring-1) at the positions of
  // the last UpdatePositions or evaluation, -1 where a bond carries no energy
  // (bond_energies, ba_force.hpp; the fracture-energy criterion, failure.hpp). Local.
  void BondEnergies(double *psi) const { bond_energies_(y_.data(), psi); }
  // V_i W_i of the listed local points (energy[k] of points[k]) at the positions of the
  // last UpdatePositions or evaluation (listed_strain_energies, ba_force.hpp). Local.
  void ListedEnergies(const std::size_t *points, std::size_t count, double *energy) const
  {
    listed_energies_(y_.data(), points, count, energy);
  }

  const double            *positions() const { return y_.data(); } // of the last evaluation
  const KernelStats       &stats() const { return stats_; }        // of the last committed evaluation
  std::vector<FailedBond> &failed_bonds() { return *failed_; } // of the last committed evaluation
  std::vector<double>     &warm_start() { return c33_; }           // checkpoints, the last good state
  void                     ForgetStats() { stats_ = KernelStats{}; }

private:
  PetscErrorCode Kernel(const double *u_owned, double *force_density, double *c33, KernelStats *stats);

  MPI_Comm                 comm_     = MPI_COMM_NULL;
  const Layout            *layout_   = nullptr;
  const Families          *families_ = nullptr;
  std::vector<double>      c33_;        // plane-stress warm start, 1 per bond
  std::vector<double>      bond_force_; // t_ij, D per bond
  std::vector<double>      y_;          // current positions, D per local point
  // The model and D, chosen once: t_ij of every bond, then f_i of the owned points.
  std::function<KernelStats(const double *y, double *c33, double *force_density)> bond_forces_;
  std::function<void(const double *y, double *energy)>     point_energies_;
  std::function<void(const double *y, double *psi)>        bond_energies_;
  std::function<void(const double *y, const std::size_t *points, std::size_t count, double *energy)> listed_energies_;
  // The kernel's workspace at the chosen D (one of the two is used); failed_ points
  // to its list of failed bonds, and keep_warm_start_ to its flag.
  nd::Workspace<2>         workspace2_;
  nd::Workspace<3>         workspace3_;
  std::vector<FailedBond> *failed_          = &workspace2_.failed;
  bool                    *keep_warm_start_ = &workspace2_.keep_warm_start;
  int                      dimension_       = 2;
  std::vector<FailedBond>  kept_failed_; // the committed list while a keep evaluation runs
  KernelStats              stats_;
  Vec                      u_ghosted_   = nullptr; // displacement with two rings of ghosts
  PetscLogStage            stage_ghost_ = 0, stage_force_ = 0;
};

} // namespace bapd
