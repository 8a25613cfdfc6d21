// The points the scene names, found among a rank's owned points at run time: the
// points a load set holds (LoadSetSelect: each region type's predicate, regions/) and
// the point a probe reads (ProbeLocate, the same point on any number of ranks); and a
// cloud's blocks, for load sets and probes by block id. The solver and the tests call
// these.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "bapd/solver/input/scene.hpp"

namespace bapd {

std::vector<double> BlockPoints(const Body<2> &body, int64_t block)
{
  std::vector<std::pair<double, double>> found;
  if (body.given_points)
    for (std::size_t p = 0; p < body.given_points->size(); ++p)
      if (body.given_points->block[p] == block) found.emplace_back(body.given_points->x[2 * p], body.given_points->x[2 * p + 1]);
  std::sort(found.begin(), found.end());
  std::vector<double> out;
  out.reserve(2 * found.size());
  for (const auto &[x, y] : found) out.insert(out.end(), {x, y});
  return out;
}

std::string BlockIdList(const std::vector<int64_t> &block)
{
  std::vector<int64_t> ids(block);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  std::string list;
  for (std::size_t k = 0; k < ids.size() && k < 20; ++k) list += (k ? ", " : "") + std::to_string(ids[k]);
  return ids.size() > 20 ? list + ", ..." : list;
}

std::string BlockIdList(const Body<2> &body) { return body.given_points ? BlockIdList(body.given_points->block) : ""; }

std::vector<double> BlockPoints3D(const std::vector<double> &x, const std::vector<int64_t> &block, int64_t id)
{
  std::vector<std::array<double, 3>> found;
  for (std::size_t p = 0; p < block.size(); ++p)
    if (block[p] == id) found.push_back({x[3 * p], x[3 * p + 1], x[3 * p + 2]});
  std::sort(found.begin(), found.end());
  std::vector<double> out;
  out.reserve(3 * found.size());
  for (const auto &q : found) out.insert(out.end(), q.begin(), q.end());
  return out;
}

namespace {
template <int D> void Select(const BodyExtent &body, const LoadSet &set, const double *x, PetscInt n, std::vector<PetscInt> *selected)
{
  selected->clear();
  for (PetscInt i = 0; i < n; ++i)
    if (LoadSetContains<D>(body, set, x + D * i)) selected->push_back(i);
}
} // namespace

PetscErrorCode LoadSetSelect(const BodyExtent &body, const LoadSet &set, const double *x, PetscInt n, std::vector<PetscInt> *selected)
{
  PetscFunctionBeginUser;
  if (body.dimension == 3) Select<3>(body, set, x, n, selected);
  else Select<2>(body, set, x, n, selected);
  PetscFunctionReturn(0);
}

// 2D: the sheet from the origin; 3D: the extent of the points' cells; the body's
// spacing (BodySection::dx).
BodyExtent BodyExtentOf(const Scene &scene)
{
  const BodySection &body = scene.body;
  BodyExtent         e;
  e.dimension = body.dimension;
  e.thickness = body.sheet.thickness;
  e.dx        = body.dx();
  if (body.dimension == 3) e.lo = body.solid_summary.lo, e.hi = body.solid_summary.hi;
  else e.hi = {body.sheet.width, body.sheet.height, 0.0};
  return e;
}

template <int D>
PetscErrorCode ProbeLocate(MPI_Comm comm, const Probe &probe, const double *x, const int64_t *natural_id, PetscInt n, ProbeLocation *location)
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  double   best_d2 = std::numeric_limits<double>::max();
  int64_t  best_id = std::numeric_limits<int64_t>::max();
  PetscInt best    = -1;
  for (PetscInt i = 0; i < n; ++i) {
    const double dx = x[D * i] - probe.x, dy = x[D * i + 1] - probe.y;
    double       d2 = dx * dx + dy * dy;
    if constexpr (D == 3) {
      const double dz = x[D * i + 2] - probe.z;
      d2              = d2 + dz * dz;
    }
    if (d2 < best_d2 || (d2 == best_d2 && natural_id[i] < best_id)) {
      best_d2 = d2;
      best_id = natural_id[i];
      best    = i;
    }
  }
  // The smallest distance, then the smallest id among the points at that distance:
  // exact comparisons are safe because every rank compares the same stored values.
  double d2min = best_d2;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &d2min, 1, MPI_DOUBLE, MPI_MIN, comm));
  int64_t id = best_d2 == d2min ? best_id : std::numeric_limits<int64_t>::max();
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &id, 1, MPI_INT64_T, MPI_MIN, comm));
  PetscMPIInt mine = (best >= 0 && best_id == id && best_d2 == d2min) ? rank : -1, owner = -1;
  PetscCallMPI(MPI_Allreduce(&mine, &owner, 1, MPI_INT, MPI_MAX, comm));
  PetscCheck(owner >= 0, comm, PETSC_ERR_ARG_WRONG, "ProbeLocate: probe '%s' found no material point: no rank passed any point",
             probe.name.c_str());
  location->owner       = owner;
  location->natural_id  = id;
  location->local_index = owner == rank ? best : -1;
  location->distance    = std::sqrt(d2min);
  PetscFunctionReturn(0);
}
template PetscErrorCode ProbeLocate<2>(MPI_Comm, const Probe &, const double *, const int64_t *, PetscInt, ProbeLocation *);
template PetscErrorCode ProbeLocate<3>(MPI_Comm, const Probe &, const double *, const int64_t *, PetscInt, ProbeLocation *);

} // namespace bapd
