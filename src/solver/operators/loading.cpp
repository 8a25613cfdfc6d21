// Loading (loading.hpp): grips, prescribed values, reactions, the moving schedule.
#include "bapd/solver/operators/loading.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "bapd/core/geometry/geometry.hpp"
#include "bapd/solver/parallel/reproducible_sum.hpp"

namespace bapd {

PetscErrorCode Loading::Setup(MPI_Comm comm, const LoadingSection &loading, double end_time, const BodyExtent &body, const Layout &layout)
{
  PetscFunctionBegin;
  comm_              = comm;
  layout_            = &layout;
  dimension_         = body.dimension;
  reference_length_  = loading.reference_length;
  schedule_          = loading.schedule;
  end_time_          = end_time;
  schedule_original_ = loading.schedule.time;
  end_time_original_ = end_time;
  load_points_.assign(loading.sets.size(), {});
  constrained_.clear();
  std::size_t most = 0;
  for (std::size_t s = 0; s < loading.sets.size(); ++s) {
    const LoadSet        &set = loading.sets[s];
    std::vector<PetscInt> selected;
    PetscCall(LoadSetSelect(body, set, layout.cloud.x.data(), layout.n_owned, &selected));
    PetscInt count = (PetscInt)selected.size();
    PetscCallMPI(MPI_Allreduce(&count, &load_points_[s].global_count, 1, MPIU_INT, MPI_SUM, comm));
    if (load_points_[s].global_count == 0) {
      // (A thin box can miss every lattice point, a hole can empty an edge layer: the
      // region type's message says which option to change. At most 767 characters.)
      const std::string msg = LoadSetEmptyMessage(body, set).substr(0, 767);
      SETERRQ(comm, PETSC_ERR_USER, "%s", msg.c_str());
    }
    most                   = std::max(most, selected.size());
    load_points_[s].points = selected;
    for (PetscInt p : selected)
      for (int c = 0; c < dimension_; ++c) {
        const ComponentLoad kind = set.component(c);
        if (kind == ComponentLoad::free) continue;
        constrained_.push_back({dimension_ * p + c, kind, set.scale(c)});
      }
  }
  // A point in two sets is held by the one named last; keep one entry per dof.
  std::vector<ConstrainedDof> unique;
  for (const ConstrainedDof &d : constrained_) {
    auto it = std::find_if(unique.begin(), unique.end(), [&](const ConstrainedDof &e) { return e.dof == d.dof; });
    if (it == unique.end()) unique.push_back(d);
    else *it = d;
  }
  constrained_ = std::move(unique);
  if (loading.grip_field == GripField::affine) PetscCall(SetAffineLevers(loading.sets, body, layout));
  terms_.assign(static_cast<std::size_t>(dimension_) * most, 0.0);
  PetscFunctionReturn(0);
}

std::vector<PetscInt> Loading::held_dofs() const
{
  std::vector<PetscInt> held;
  for (const ConstrainedDof &d : constrained_) held.push_back(d.dof);
  return held;
}

void Loading::Apply(double t, double *u, double *v) const
{
  const double L = reference_length_, lambda = schedule_.stretch_at(t), rate = schedule_.rate_at(t);
  for (const ConstrainedDof &d : constrained_) {
    if (d.kind == ComponentLoad::fixed) {
      u[d.dof] = 0.0;
      if (v) v[d.dof] = 0.0;
    } else {
      u[d.dof] = d.scale * (lambda - 1.0) * L;
      if (v) v[d.dof] = d.scale * rate * L;
    }
    if (d.lever != 0.0) { // -load_grip_field affine (the rigid default: no term, the same bits)
      u[d.dof] += d.lever * (lambda - 1.0);
      if (v) v[d.dof] += d.lever * rate;
    }
  }
}

// -load_grip_field affine: the y dofs of the top and bottom grips get
// lever = (L / L_free) (y - y_inner), y_inner the grip line: the specimen's edge, H
// (top) or 0 (bottom), for a grip outside it; H - layers dx or layers dx for one
// inside (a 3D body's faces y = hi and lo of its extent, its grips always inside).
// L_free = y_inner,top - y_inner,bottom (CheckLoading made sure both exist).
// The x dofs keep what the set says: a clamp holds x (the free region's lateral
// contraction vanishes at the grip line, so u_x = 0 continues it).
// Two region grips (box, polygon, curve, group, block: no edge set holds y) are the
// same for any shape: the grip line of each is where its points end towards the
// other, half a point spacing (sqrt(V/t)) beyond its innermost point; the upper set
// is the top grip, and the two must not overlap in y. That is the outside treatment's
// equivalent for grips on the body's own points (docs/options.md, "The outside
// treatment for region grips"); in 3D the half spacing is cbrt(V) / 2.
PetscErrorCode Loading::SetAffineLevers(const std::vector<LoadSet> &sets, const BodyExtent &body, const Layout &layout)
{
  const double face_lo = body.lo[1], face_hi = body.hi[1]; // (2D: 0 and the sheet's height)
  const double dx      = body.dx;
  double       y_top = 0, y_bottom = 0;
  bool         edge  = false;
  PetscFunctionBegin;
  for (const LoadSet &l : sets) {
    if (l.y == ComponentLoad::free) continue;
    const bool inside = l.placement == GripPlacement::inside;
    if (l.region == LoadSet::Region::top) y_top = inside ? face_hi - l.layers * dx : face_hi, edge = true;
    if (l.region == LoadSet::Region::bottom) y_bottom = inside ? face_lo + l.layers * dx : face_lo, edge = true;
  }
  if (!edge) { // two region grips (CheckLoading): their extent in y, the same on any rank count (min/max)
    double      lo[2], hi[2]; // per set: lowest y - h/2, -(highest y + h/2)
    std::size_t k = 0;
    const char *names[2] = {"", ""};
    for (std::size_t s = 0; s < sets.size(); ++s) {
      if (sets[s].y == ComponentLoad::free) continue;
      lo[k] = hi[k] = std::numeric_limits<double>::max();
      for (PetscInt p : load_points_[s].points) {
        const double V = layout.cloud.volume[p];
        const double y = layout.cloud.x[dimension_ * p + 1], h = point_spacing(dimension_, V, body.thickness);
        lo[k]          = std::min(lo[k], y - 0.5 * h);
        hi[k]          = std::min(hi[k], -(y + 0.5 * h));
      }
      names[k++] = sets[s].name.c_str();
    }
    PetscCheck(k == 2, comm_, PETSC_ERR_PLIB, "SetAffineLevers: %zu region grips hold y, not 2", k);
    double ext[4] = {lo[0], hi[0], lo[1], hi[1]};
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, ext, 4, MPI_DOUBLE, MPI_MIN, comm_));
    const int top = ext[2] > ext[0] ? 1 : 0, bottom = 1 - top;
    y_top         = ext[2 * top];
    y_bottom      = -ext[2 * bottom + 1];
    PetscCheck(y_top >= y_bottom, comm_, PETSC_ERR_USER,
               "-load_grip_field affine: load sets '%s' and '%s' overlap in y (the lower reaches y = %g m, the upper starts at %g m): an "
               "affine grip field needs a top grip wholly above a bottom grip; use -load_grip_field rigid, or grips that do not overlap",
               names[bottom], names[top], y_bottom, y_top);
  }
  const double gradient = reference_length_ / (y_top - y_bottom);
  for (ConstrainedDof &d : constrained_) {
    if (d.dof % dimension_ != 1) continue;
    const double y = layout.cloud.x[d.dof]; // (D p + 1: the y of point p)
    if (y > y_top) d.lever = gradient * (y - y_top);
    else if (y < y_bottom) d.lever = gradient * (y - y_bottom);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Loading::Reactions(const double *force_density, double *reaction)
{
  const double *volume = layout_->cloud.volume.data();

  PetscFunctionBegin;
  for (std::size_t s = 0; s < load_points_.size(); ++s) {
    const std::vector<PetscInt> &pts = load_points_[s].points;
    const int D = dimension_;
    for (std::size_t k = 0; k < pts.size(); ++k)
      for (int c = 0; c < D; ++c) terms_[D * k + c] = -force_density[D * pts[k] + c] * volume[pts[k]];
    PetscCall(ReproducibleSum(comm_, D, (PetscInt)pts.size(), terms_.data(), &reaction[D * s]));
  }
  PetscFunctionReturn(0);
}

PetscInt Loading::segment_at(double t) const
{
  return (PetscInt)(std::upper_bound(schedule_.time.begin(), schedule_.time.end(), t) - schedule_.time.begin());
}

PetscInt Loading::HoldAt(double t) const
{
  const Schedule &s = schedule_;
  if (s.time.empty() || s.rate_at(t) != 0.0 || t < s.time.front()) return -1;
  const PetscInt k = segment_at(t) - 1; // t in [time[k], time[k+1])
  return k == hold_done_ ? -1 : k;
}

void Loading::EndHold(PetscInt k, double t)
{
  Schedule    &s         = schedule_;
  const double hold_end  = k + 1 < (PetscInt)s.time.size() ? s.time[k + 1] : end_time_;
  const double remaining = std::max(0.0, hold_end - t);
  for (std::size_t j = (std::size_t)k + 1; j < s.time.size(); ++j) s.time[j] -= remaining;
  end_time_  = std::max(t, end_time_ - remaining);
  hold_done_ = k;
}

// Static holds that ended early moved the later knots and the end time; the same
// schedule (the common case) takes the moved values exactly, a schedule or end time
// changed on the restart command line takes the same shifts.
PetscErrorCode Loading::Restore(const std::vector<double> &original, const std::vector<double> &current, double end_original,
                                double end_current, double t, PetscInt hold_done)
{
  Schedule &s = schedule_;

  PetscFunctionBegin;
  if (current.size() == s.time.size()) {
    for (std::size_t k = 0; k < s.time.size(); ++k) s.time[k] = s.time[k] == original[k] ? current[k] : s.time[k] + (current[k] - original[k]);
  } else if (current != original) {
    PetscCall(PetscPrintf(comm_, "Note: the load schedule has other knots than the checkpoint's; the holds it ended early are not carried over\n"));
  }
  end_time_  = end_time_ == end_original ? end_current : std::max(t, end_time_ + (end_current - end_original));
  hold_done_ = hold_done;
  PetscFunctionReturn(0);
}

} // namespace bapd
