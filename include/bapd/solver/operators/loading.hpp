#pragma once
// Loading: which components the grips hold, the stretch schedule they follow, the
// values they prescribe and the reactions they supply. The
// schedule and the end time start as the scene's and change only here: a static
// hold that ends early moves the later knots (EndHold), and a restart puts the moved
// schedule back (Restore). The scene itself is never written.
// The dimension D = scene.body.dimension (2 or 3) is taken at Setup: a
// point has D dofs (D p + c) and a load set D reaction components. It is a run-time
// value, not a template parameter, because nothing here runs per bond (the grips'
// dofs once a step) and the time-step control takes a Loading of either D.
#include <petscsys.h>

#include <vector>

#include "bapd/solver/parallel/layout.hpp"
#include "bapd/solver/input/scene.hpp"

namespace bapd {

// One loaded component of one owned point.
struct ConstrainedDof {
  PetscInt      dof;   // D * owned point + component
  ComponentLoad kind;  // fixed or stretch
  double        scale; // u = scale * (lambda - 1) * reference_length
  double        lever = 0.0; // -load_grip_field affine: + lever * (lambda - 1) [m]
};

struct LoadSetPoints {
  std::vector<PetscInt> points; // owned local indices
  PetscInt              global_count = 0;
};

class Loading {
public:
  // Selects the points of every load set (LoadSetSelect) of the body `body`; a set that
  // holds no point anywhere is an error naming its option. end_time: the run's
  // (-end_time), which the static holds move. Collective.
  PetscErrorCode Setup(MPI_Comm comm, const LoadingSection &loading, double end_time, const BodyExtent &body, const Layout &layout);

  // Holds the loaded components at their prescribed values (v may be nullptr): exact
  // for any TS type.
  void Apply(double t, double *u, double *v) const;
  // Reactions of every load set (x, y[, z] per set: D * sets values): the grip holds its
  // points still, so it supplies minus the internal force, sum_i -f_i V_i. A
  // reproducible sum: the same bits on any number of ranks. Collective; no allocation.
  // The history rows and the summary both report these.
  PetscErrorCode Reactions(const double *force_density, double *reaction);

  const std::vector<ConstrainedDof> &constrained() const { return constrained_; }
  const std::vector<LoadSetPoints>  &load_set_points() const { return load_points_; } // the load sets' order
  std::vector<PetscInt>              held_dofs() const;
  const Schedule                    &schedule() const { return schedule_; }
  double                             end_time() const { return end_time_; }
  double                             stretch_at(double t) const { return schedule_.stretch_at(t); }
  PetscInt                           segment_at(double t) const; // schedule knots passed at t
  int                                dimension() const { return dimension_; }

  // Static holds: the knot k whose hold t lies in, if that hold has not ended yet
  // (else -1); EndHold(k, t) skips what is left of it, moving the later knots and the
  // end time earlier.
  PetscInt HoldAt(double t) const;
  void     EndHold(PetscInt k, double t);
  PetscInt hold_done() const { return hold_done_; }
  const std::vector<double> &schedule_original() const { return schedule_original_; }
  double                     end_time_original() const { return end_time_original_; }
  // Restart: the schedule and end time as the checkpoint had them (moved by the holds
  // it ended), carried over to the schedule read now. Collective (prints).
  PetscErrorCode Restore(const std::vector<double> &original, const std::vector<double> &current, double end_original,
                         double end_current, double t, PetscInt hold_done);

private:
  PetscErrorCode SetAffineLevers(const std::vector<LoadSet> &sets, const BodyExtent &body, const Layout &layout); // collective

  MPI_Comm                    comm_   = MPI_COMM_NULL;
  const Layout               *layout_ = nullptr;
  int                         dimension_ = 2; // D: dofs a point
  double                      reference_length_ = 0;
  std::vector<ConstrainedDof> constrained_;
  std::vector<LoadSetPoints>  load_points_;
  std::vector<double>         terms_; // reaction terms, sized once
  Schedule                    schedule_;
  double                      end_time_ = 0;
  std::vector<double>         schedule_original_; // the knot times as this run read them
  double                      end_time_original_ = 0;
  PetscInt                    hold_done_         = -1; // schedule knot whose hold already ended
};

} // namespace bapd
