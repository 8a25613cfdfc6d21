#include "bapd/solver/parallel/natural_order.hpp"

#include <algorithm>

namespace bapd {

namespace {

// Rank r holds natural ids [start(r), start(r) + count(r)): the first n % size ranks
// one more than the others (PetscSplitOwnership's rule), so any rank count works.
struct Blocks {
  PetscInt n, size;
  PetscInt count(PetscInt r) const { return n / size + (r < n % size ? 1 : 0); }
  PetscInt start(PetscInt r) const { return r * (n / size) + std::min(r, n % size); }
  PetscInt owner(PetscInt id) const
  {
    const PetscInt base = n / size, extra = n % size;
    if (id < extra * (base + 1)) return id / (base + 1);
    return extra + (id - extra * (base + 1)) / base;
  }
};

PetscErrorCode CreateSF(MPI_Comm comm, PetscInt nroots, std::vector<PetscSFNode> &remote, PetscSF *sf)
{
  PetscFunctionBegin;
  PetscCall(PetscSFCreate(comm, sf));
  PetscCall(PetscSFSetGraph(*sf, nroots, (PetscInt)remote.size(), nullptr, PETSC_COPY_VALUES, remote.data(), PETSC_COPY_VALUES));
  PetscCall(PetscSFSetUp(*sf));
  PetscFunctionReturn(0);
}

} // namespace

NaturalOrder::~NaturalOrder()
{
  PetscSFDestroy(&owned_points);
  PetscSFDestroy(&family_points);
  PetscSFDestroy(&owned_bonds);
  PetscSFDestroy(&family_bonds);
}

PetscErrorCode NaturalOrderCreate(MPI_Comm comm, const Layout &layout, const Families &families, NaturalOrder *order)
{
  PetscMPIInt rank, size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  const Blocks   blocks{layout.n_global, size};
  const PetscInt n_owned = layout.n_owned, n_family = layout.n_family();
  order->n_points    = layout.n_global;
  order->point_start = blocks.start(rank);
  order->point_count = blocks.count(rank);

  // Points: leaf i -> (owner of its natural id, place in that block).
  std::vector<PetscSFNode> remote(n_family);
  for (PetscInt i = 0; i < n_family; ++i) {
    const PetscInt id = (PetscInt)layout.cloud.natural_id[i], r = blocks.owner(id);
    remote[i].rank    = r;
    remote[i].index   = id - blocks.start(r);
  }
  PetscCall(CreateSF(comm, order->point_count, remote, &order->family_points));
  std::vector<PetscSFNode> owned(remote.begin(), remote.begin() + n_owned);
  PetscCall(CreateSF(comm, order->point_count, owned, &order->owned_points));

  // Family sizes in natural order, then each block point's first bond: a prefix sum
  // inside the block plus the bonds of the blocks before it.
  std::vector<PetscInt> size_local(n_family);
  for (PetscInt i = 0; i < n_family; ++i) size_local[i] = (PetscInt)families.size((std::size_t)i);
  order->family_size.assign(order->point_count, 0);
  PetscCall(ToNaturalOrder(order->owned_points, MPIU_INT, size_local.data(), order->family_size.data()));
  std::vector<PetscInt> first_bond(order->point_count);
  PetscInt              in_block = 0;
  for (PetscInt k = 0; k < order->point_count; ++k) {
    first_bond[k] = in_block;
    in_block += order->family_size[k];
  }
  PetscInt before = 0;
  PetscCallMPI(MPI_Exscan(&in_block, &before, 1, MPIU_INT, MPI_SUM, comm));
  if (rank == 0) before = 0; // MPI_Exscan leaves rank 0's result undefined
  for (PetscInt &f : first_bond) f += before;
  order->bond_start = before;
  order->bond_count = in_block;
  PetscCallMPI(MPI_Allreduce(&in_block, &order->n_bonds, 1, MPIU_INT, MPI_SUM, comm));

  // Every family point learns its first bond and its owner's family size: a ring-1
  // copy of a family is the owner's family (family.hpp), checked here.
  std::vector<PetscInt> first_local(n_family), size_check(n_family);
  PetscCall(FromNaturalOrder(order->family_points, MPIU_INT, first_bond.data(), first_local.data()));
  PetscCall(FromNaturalOrder(order->family_points, MPIU_INT, order->family_size.data(), size_check.data()));
  PetscInt mismatch = 0;
  for (PetscInt i = 0; i < n_family; ++i) mismatch += size_check[i] != size_local[i];
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &mismatch, 1, MPIU_INT, MPI_SUM, comm));
  PetscCheck(mismatch == 0, comm, PETSC_ERR_PLIB, "NaturalOrderCreate: %" PetscInt_FMT " ghost families differ from their owners'", mismatch);

  // Bonds: bond q of family point i is global bond first(i) + q, held by the rank
  // that holds point i's natural id.
  std::vector<PetscInt> bond_starts(size);
  PetscCallMPI(MPI_Allgather(&order->bond_start, 1, MPIU_INT, bond_starts.data(), 1, MPIU_INT, comm));
  std::vector<PetscSFNode> bond_remote(families.offsets[n_family]);
  for (PetscInt i = 0; i < n_family; ++i) {
    const PetscInt r = remote[i].rank;
    for (std::size_t b = families.offsets[i]; b < families.offsets[i + 1]; ++b) {
      bond_remote[b].rank  = r;
      bond_remote[b].index = first_local[i] + (PetscInt)(b - families.offsets[i]) - bond_starts[r];
    }
  }
  PetscCall(CreateSF(comm, order->bond_count, bond_remote, &order->family_bonds));
  bond_remote.resize(families.offsets[n_owned]);
  PetscCall(CreateSF(comm, order->bond_count, bond_remote, &order->owned_bonds));
  PetscFunctionReturn(0);
}

PetscErrorCode ToNaturalOrder(PetscSF sf, MPI_Datatype unit, const void *local, void *block)
{
  PetscFunctionBegin;
  PetscCall(PetscSFReduceBegin(sf, unit, local, block, MPI_REPLACE));
  PetscCall(PetscSFReduceEnd(sf, unit, local, block, MPI_REPLACE));
  PetscFunctionReturn(0);
}

PetscErrorCode FromNaturalOrder(PetscSF sf, MPI_Datatype unit, const void *block, void *local)
{
  PetscFunctionBegin;
  PetscCall(PetscSFBcastBegin(sf, unit, block, local, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(sf, unit, block, local, MPI_REPLACE));
  PetscFunctionReturn(0);
}

namespace {

// The MPI type of per_entry doubles, made for one exchange and freed again.
PetscErrorCode MoveDoubles(PetscSF sf, int per_entry, const double *from, double *to, bool to_natural)
{
  MPI_Datatype unit;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Type_contiguous(per_entry, MPI_DOUBLE, &unit));
  PetscCallMPI(MPI_Type_commit(&unit));
  const PetscErrorCode moved = to_natural ? ToNaturalOrder(sf, unit, from, to) : FromNaturalOrder(sf, unit, from, to);
  PetscCallMPI(MPI_Type_free(&unit));
  PetscCall(moved);
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode DoublesToNaturalOrder(PetscSF sf, int per_entry, const double *local, double *block)
{
  return MoveDoubles(sf, per_entry, local, block, true);
}

PetscErrorCode DoublesFromNaturalOrder(PetscSF sf, int per_entry, const double *block, double *local)
{
  return MoveDoubles(sf, per_entry, block, local, false);
}

} // namespace bapd
