#pragma once
// The layout-independent order of output and checkpoints.
//
// Files hold every point in natural-id order and every bond in the order
// (natural id of its point, then its place in that point's family), which is the
// natural-id order of the neighbours (family.hpp). Rank r reads and writes one
// contiguous block of natural ids, [point_start, point_start + point_count), and the
// bonds of exactly those points, [bond_start, bond_start + bond_count): a plain
// hyperslab, whatever the METIS partition. Four PetscSFs move data between the rank
// layout (leaves) and those blocks (roots): owned points / owned bonds for writing
// (each root has exactly one leaf), family points (owned + ring-1) / their bonds for
// reading back a checkpoint (ring-1 ghosts take their owner's values).
#include <petscsf.h>

#include <vector>

#include "bapd/core/geometry/family.hpp"
#include "bapd/solver/parallel/layout.hpp"

namespace bapd {

struct NaturalOrder {
  PetscInt n_points = 0, point_start = 0, point_count = 0; // this rank's block of natural ids
  PetscInt n_bonds = 0, bond_start = 0, bond_count = 0;    // the bonds of those points
  std::vector<PetscInt> family_size;                       // per block point (from its owner)
  PetscSF owned_points  = nullptr; // leaves: owned points [0, n_owned)
  PetscSF family_points = nullptr; // leaves: owned + ring-1 points [0, n_family)
  PetscSF owned_bonds   = nullptr; // leaves: bonds of owned points [0, offsets[n_owned])
  PetscSF family_bonds  = nullptr; // leaves: bonds of family points [0, offsets[n_family])

  NaturalOrder() = default;
  ~NaturalOrder();
  NaturalOrder(const NaturalOrder &)            = delete;
  NaturalOrder &operator=(const NaturalOrder &) = delete;
  bool created() const { return owned_points != nullptr; }
};

// Collective. Builds the blocks and the four maps for this layout and its families.
PetscErrorCode NaturalOrderCreate(MPI_Comm comm, const Layout &layout, const Families &families, NaturalOrder *order);

// Layout -> block (each block entry has one owner): `unit` is the MPI type of one
// entry (e.g. D doubles per point). sf is owned_points or owned_bonds.
PetscErrorCode ToNaturalOrder(PetscSF sf, MPI_Datatype unit, const void *local, void *block);
// Block -> layout: sf is any of the four maps.
PetscErrorCode FromNaturalOrder(PetscSF sf, MPI_Datatype unit, const void *block, void *local);
// The same for `per_entry` doubles an entry (a D-vector a point: D; a run-time count
// because it is only the size of the unit moved, whatever it means).
PetscErrorCode DoublesToNaturalOrder(PetscSF sf, int per_entry, const double *local, double *block);
PetscErrorCode DoublesFromNaturalOrder(PetscSF sf, int per_entry, const double *block, double *local);

} // namespace bapd
