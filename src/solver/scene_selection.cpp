// The points the scene names, found among a rank's owned points at run time: the
// points a load set holds (LoadSetSelect) and the point a probe reads (ProbeLocate,
// the same point on any number of ranks). The solver and the tests call these.
#include <cstdint>
#include <limits>
#include <vector>

#include "bapd/scene.hpp"

namespace bapd {

PetscErrorCode LoadSetSelect(const Scene &scene, const LoadSet &set, const double *x, PetscInt n, std::vector<PetscInt> *selected)
{
  const Body2D &b     = scene.body;
  const double  depth = set.layers * b.dx; // layer boundaries fall half-way between lattice rows
  PetscFunctionBeginUser;
  selected->clear();
  for (PetscInt i = 0; i < n; ++i) {
    const double px = x[2 * i], py = x[2 * i + 1];
    bool         in = false;
    if (set.placement == GripPlacement::outside) switch (set.region) {
      case LoadSet::Region::top: in = py > b.height && py < b.height + depth; break;
      case LoadSet::Region::bottom: in = py < 0 && py > -depth; break;
      case LoadSet::Region::left: in = px < 0 && px > -depth; break;
      case LoadSet::Region::right: in = px > b.width && px < b.width + depth; break;
      case LoadSet::Region::box: break; // (a box is inside)
      }
    else switch (set.region) {
         // (not the rows of other grips placed outside the sheet)
      case LoadSet::Region::top: in = py > b.height - depth && py < b.height; break;
      case LoadSet::Region::bottom: in = py < depth && py > 0; break;
      case LoadSet::Region::left: in = px < depth && px > 0; break;
      case LoadSet::Region::right: in = px > b.width - depth && px < b.width; break;
      case LoadSet::Region::box: in = px >= set.box[0] && px <= set.box[2] && py >= set.box[1] && py <= set.box[3]; break;
      }
    if (in) selected->push_back(i);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ProbeLocate(MPI_Comm comm, const Probe &probe, const double *x, const int64_t *natural_id, PetscInt n, ProbeLocation *location)
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  double   best_d2 = std::numeric_limits<double>::max();
  int64_t  best_id = std::numeric_limits<int64_t>::max();
  PetscInt best    = -1;
  for (PetscInt i = 0; i < n; ++i) {
    const double dx = x[2 * i] - probe.x, dy = x[2 * i + 1] - probe.y, d2 = dx * dx + dy * dy;
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

} // namespace bapd
