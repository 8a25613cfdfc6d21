#pragma once
// Scaffolding of the tests of the run-time data layer in D = 2 and 3 (halo_3d,
// checkpoint_3d, fields_3d): a box lattice (nd::box_lattice<D>) partitioned and
// distributed over a communicator the way Simulation::BuildBody does it, and values
// that are a function of a point's natural id, so that any rank can say what any
// point must hold, with tolerance 0.
#include <petscsys.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "bapd/core/geometry/family.hpp"
#include "bapd/solver/parallel/layout.hpp"

namespace bapd_test {

inline constexpr double kBoxDx = 1e-3;

// One rank's share of a box of cells[0] x ... x cells[D-1] points, dx = kBoxDx.
struct BoxLayout {
  bapd::PointCloud global;   // the whole box with its family volumes, on every rank
  bapd::Families   families; // of the whole box (natural order), on every rank
  bapd::Layout     layout;   // this rank's points
  bapd::Families   local;    // the families of this rank's owned and ring-1 points
  double           horizon = 0;
};

// Collective on comm. Every rank builds the whole box (small), rank 0's bond graph is
// partitioned, and every rank finds the families of its owned and ring-1 points from
// the two rings it holds (Simulation::BuildBody). own_horizons: the points get their
// own horizons (geometry.hpp), 1, 0.95 and 0.9 times horizon_factor dx in turn.
template <int D>
PetscErrorCode MakeBoxLayout(MPI_Comm comm, const std::array<int, D> &cells, double horizon_factor, BoxLayout *box,
                             bool own_horizons = false)
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  box->horizon  = horizon_factor * kBoxDx;
  box->global   = bapd::nd::box_lattice<D>(cells, kBoxDx);
  if (own_horizons)
    for (std::size_t i = 0; i < box->global.size(); ++i) box->global.horizon.push_back(box->horizon * (1.0 - 0.05 * (double)(i % 3)));
  box->families = bapd::nd::build_families<D>(box->global, box->global.size(), box->horizon);
  bapd::compute_family_volumes(box->global, box->families);
  std::vector<int> offsets, neighbours;
  if (rank == 0) {
    offsets.assign(box->families.offsets.begin(), box->families.offsets.end());
    neighbours.assign(box->families.neighbour.begin(), box->families.neighbour.end());
  }
  PetscCall(bapd::DistributePoints<D>(comm, box->global, offsets, neighbours, &box->layout));
  box->local = bapd::nd::build_families<D>(box->layout.cloud, (std::size_t)box->layout.n_family(), box->horizon);
  PetscFunctionReturn(0);
}

// A value of component c of point `id` that every component, point and tag tells apart
// and that is exact in binary (a multiple of 1/8).
inline double PointValue(std::int64_t id, int c, int tag) { return 0.125 * (double)(1000 * id + 10 * c + tag) - 3.0; }

// A bond rule that both directed copies of a bond agree on: broken iff this holds.
inline bool BrokenBond(std::int64_t a, std::int64_t b)
{
  const std::int64_t lo = a < b ? a : b, hi = a < b ? b : a;
  return (7 * lo + 3 * hi) % 11 == 0;
}

// The message of the error that started the last failure (PETSc keeps it).
inline std::string LastErrorText()
{
  const char *generic  = nullptr;
  char       *specific = nullptr;
  PetscErrorMessage(PETSC_ERR_USER, &generic, &specific);
  return specific ? specific : "";
}

} // namespace bapd_test
