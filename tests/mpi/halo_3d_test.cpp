// The layout in 3D: a 3D box distributed over the ranks holds every
// point once, gives each rank the positions of its two rings exactly, and the families
// built from them are the whole body's; a ghosted Vec of block size 3 carries each
// owner's three components to every ghost copy unchanged.
#include <gtest/gtest.h>

#include <set>

#include "mpi/box_layout.hpp"

using namespace bapd;
using bapd_test::BoxLayout;

namespace {

class Halo3D : public ::testing::Test {
protected:
  void SetUp() override
  {
    // 12 x 6 x 5 points at delta = 3.015 dx (the paper's horizon), every third point's
    // own horizon 5 % and 10 % shorter (given points carry theirs through the layout):
    // families of up to 119 members (two mask words), and long enough in x for ring-2
    // ghosts on 2 and 3 ranks.
    ASSERT_EQ(bapd_test::MakeBoxLayout<3>(PETSC_COMM_WORLD, {12, 6, 5}, 3.015, &box, true), 0);
  }
  BoxLayout box;
};

TEST_F(Halo3D, EveryPointIsOwnedOnceAndTheRingsHoldTheirExactPositions)
{
  const Layout &l = box.layout;
  ASSERT_EQ(l.dimension, 3);
  ASSERT_EQ(l.n_global, 360);
  ASSERT_EQ(l.cloud.x.size(), 3 * (std::size_t)l.n_local());
  ASSERT_EQ(l.cloud.horizon.size(), (std::size_t)l.n_local());
  PetscInt owned = l.n_owned;
  MPI_Allreduce(MPI_IN_PLACE, &owned, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD);
  EXPECT_EQ(owned, l.n_global);
  std::vector<int> count(l.n_global, 0);
  for (PetscInt i = 0; i < l.n_owned; ++i) count[l.cloud.natural_id[i]] += 1;
  MPI_Allreduce(MPI_IN_PLACE, count.data(), (int)count.size(), MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
  for (int c : count) EXPECT_EQ(c, 1);
  // Reference data of every local point, owned and ghost, bit for bit the whole box's.
  for (PetscInt i = 0; i < l.n_local(); ++i) {
    const std::size_t id = (std::size_t)l.cloud.natural_id[i];
    for (int d = 0; d < 3; ++d) EXPECT_EQ(l.cloud.x[3 * i + d], box.global.x[3 * id + d]) << "point " << id;
    EXPECT_EQ(l.cloud.volume[i], box.global.volume[id]);
    EXPECT_EQ(l.cloud.family_volume[i], box.global.family_volume[id]);
    EXPECT_EQ(l.cloud.horizon[i], box.global.horizon[id]);
  }
}

TEST_F(Halo3D, FamiliesFromTheTwoRingsAreTheWholeBodys)
{
  // Ring 1 holds every member of an owned point's family, ring 2 every member of a
  // ring-1 point's family: the families found on the rank (natural ids, in order) are
  // the whole body's, for owned and ring-1 points alike.
  const Layout &l = box.layout;
  for (PetscInt i = 0; i < l.n_family(); ++i) {
    const std::size_t id = (std::size_t)l.cloud.natural_id[i];
    ASSERT_EQ(box.local.size((std::size_t)i), box.families.size(id)) << "point " << id;
    for (std::size_t q = 0; q < box.families.size(id); ++q)
      EXPECT_EQ(l.cloud.natural_id[box.local.neighbour[box.local.offsets[i] + q]], box.families.neighbour[box.families.offsets[id] + q]);
  }
}

TEST_F(Halo3D, GhostsOfABlockSize3VecEqualTheirOwners)
{
  const Layout &l = box.layout;
  Vec           u, local;
  PetscInt      bs = 0, n_local_form = 0;
  double       *a;
  ASSERT_EQ(CreateGhostedVector<3>(PETSC_COMM_WORLD, l, &u), 0);
  ASSERT_EQ(VecGetBlockSize(u, &bs), 0);
  EXPECT_EQ(bs, 3);
  ASSERT_EQ(VecGetArray(u, &a), 0);
  for (PetscInt i = 0; i < l.n_owned; ++i)
    for (int c = 0; c < 3; ++c) a[3 * i + c] = bapd_test::PointValue(l.cloud.natural_id[i], c, 1);
  ASSERT_EQ(VecRestoreArray(u, &a), 0);
  ASSERT_EQ(VecGhostUpdateBegin(u, INSERT_VALUES, SCATTER_FORWARD), 0);
  ASSERT_EQ(VecGhostUpdateEnd(u, INSERT_VALUES, SCATTER_FORWARD), 0);
  ASSERT_EQ(VecGhostGetLocalForm(u, &local), 0);
  ASSERT_EQ(VecGetLocalSize(local, &n_local_form), 0);
  EXPECT_EQ(n_local_form, 3 * l.n_local());
  ASSERT_EQ(VecGetArray(local, &a), 0);
  int ghosts_checked = 0;
  for (PetscInt i = 0; i < l.n_local(); ++i)
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(a[3 * i + c], bapd_test::PointValue(l.cloud.natural_id[i], c, 1)) << "local point " << i << " component " << c;
      ghosts_checked += i >= l.n_owned;
    }
  ASSERT_EQ(VecRestoreArray(local, &a), 0);
  ASSERT_EQ(VecGhostRestoreLocalForm(u, &local), 0);
  VecDestroy(&u);
  EXPECT_EQ(ghosts_checked, 3 * l.n_ghost());
  PetscMPIInt size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  PetscInt rings[2] = {l.n_ring1, l.n_ring2}; // the exchange had ghosts of both rings to fill
  MPI_Allreduce(MPI_IN_PLACE, rings, 2, MPIU_INT, MPI_MIN, PETSC_COMM_WORLD);
  if (size > 1) {
    EXPECT_GT(rings[0], 0);
    EXPECT_GT(rings[1], 0);
  }
}

TEST_F(Halo3D, AGhostedVectorOfTheOtherDimensionIsRefused)
{
  Vec u = nullptr;
  ASSERT_EQ(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr), 0);
  EXPECT_NE(CreateGhostedVector<2>(PETSC_COMM_WORLD, box.layout, &u), 0);
  PetscPopErrorHandler();
  EXPECT_EQ(u, nullptr);
}

} // namespace
