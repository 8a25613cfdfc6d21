#pragma once
// Probes (-probes): material points whose displacement is recorded, and the one rule
// that finds them on any number of ranks. Included by scene.hpp.
#include <petscsys.h>
#include <cstdint>
#include <string>

namespace bapd {

struct Probe {
  std::string name;
  double      x = 0, y = 0; // the material point nearest to (x, y) is recorded
  double      z = 0;        // 3D only (BodySection::dimension 3): (x, y, z)
};

// Where a probe reads: the point nearest to (probe.x, probe.y[, probe.z]), ties broken by the
// lowest natural id, so the choice is the same on any number of ranks.
struct ProbeLocation {
  PetscMPIInt owner       = -1; // rank that owns the point
  int64_t     natural_id  = -1;
  PetscInt    local_index = -1; // index into the owner's x; -1 on the other ranks
  double      distance    = 0;  // from (probe.x, probe.y) to the point [m]
};
// Collective. x: owned reference positions (D per point: the 2D driver's default, or
// the 3D driver's 3, where the distance is to (probe.x, probe.y, probe.z)),
// natural_id: their ids.
template <int D = 2>
PetscErrorCode ProbeLocate(MPI_Comm comm, const Probe &probe, const double *x, const int64_t *natural_id, PetscInt n,
                           ProbeLocation *location);

} // namespace bapd
