// Checkpoints in 3D: a 3D state written on 2 ranks reads back on 1
// and on 3 ranks exactly (D-vectors, bond states, C33, the relaxation's and the time
// step's vectors); a file without C33 reads as the cold start; a checkpoint continues
// only in its own dimension, with one message naming the file and both dimensions;
// a file of format 5 (no dimension attribute) reads as 2D; a damaged
// dimension is refused. Run on 3 ranks (fewer: the same with the ranks there are).
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cstdio>
#include <functional>

#include "bapd/solver/io/checkpoint.hpp"
#include "bapd/solver/parallel/natural_order.hpp"
#include "mpi/box_layout.hpp"

using namespace bapd;
using bapd_test::BoxLayout;
using bapd_test::PointValue;

namespace {

// C33 of the bond (a -> b): exact in binary, differs between the two copies of a bond.
double BondValue(std::int64_t a, std::int64_t b) { return 1.0 + 0.125 * (double)((37 * a + b) % 97); }

enum Tag { kU = 1, kV, kRelaxationU, kRelaxationA, kEigenvector };

// A state of a box layout that is a function of the natural ids, and its header.
template <int D>
struct KnownState {
  std::vector<double> u, v, relaxation_u, relaxation_a, eigenvector, c33;
  BondState           bonds;
  CheckpointHeader    header;

  explicit KnownState(const BoxLayout &box)
  {
    const Layout  &l   = box.layout;
    const Families &f  = box.local;
    auto           vec = [&](int tag) {
      std::vector<double> out(D * l.n_owned);
      for (PetscInt i = 0; i < l.n_owned; ++i)
        for (int c = 0; c < D; ++c) out[D * i + c] = PointValue(l.cloud.natural_id[i], c, tag);
      return out;
    };
    u = vec(kU), v = vec(kV), relaxation_u = vec(kRelaxationU), relaxation_a = vec(kRelaxationA), eigenvector = vec(kEigenvector);
    bonds = BondState(f);
    c33.assign(f.n_bonds(), 0.0);
    for (std::size_t i = 0; i < f.n_family; ++i)
      for (std::size_t b = f.offsets[i]; b < f.offsets[i + 1]; ++b) {
        const std::int64_t a = l.cloud.natural_id[i], n = l.cloud.natural_id[f.neighbour[b]];
        c33[b]               = BondValue(a, n);
        if (bapd_test::BrokenBond(a, n)) break_bond(f, bonds, i, b - f.offsets[i]);
      }
    header.step = 17, header.time = 0.25, header.time_step = 1e-3, header.stretch = 1.5, header.reason = "test";
    header.schedule_original = header.schedule_current = {0.0, 1.0};
    header.end_time_original = header.end_time = 1.0;
    header.relaxation_records = 3;
    header.step_lambda = 2.5e6, header.step_stiffness_dt = 1e-3, header.step_shortest = 5e-4;
    header.step_next_estimate = 40, header.step_interval_now = 20, header.step_stretch = 1.25;
  }
  CheckpointState View(bool with_c33)
  {
    CheckpointState s;
    s.u = u.data(), s.v = v.data(), s.bonds = &bonds, s.c33 = with_c33 ? c33.data() : nullptr;
    s.relaxation_u = relaxation_u.data(), s.relaxation_a = relaxation_a.data(), s.step_eigenvector = eigenvector.data();
    return s;
  }
};

// Everything a checkpoint needs from a box on comm.
template <int D>
struct Box {
  BoxLayout           box;
  NaturalOrder        order;
  GeometryFingerprint geometry;
  PetscErrorCode      Make(MPI_Comm comm, const std::array<int, D> &cells)
  {
    PetscFunctionBegin;
    PetscCall(bapd_test::MakeBoxLayout<D>(comm, cells, 3.015, &box));
    PetscCall(NaturalOrderCreate(comm, box.layout, box.local, &order));
    PetscCall(ComputeGeometryFingerprint<D>(comm, box.layout, box.local, bapd_test::kBoxDx, box.horizon, &geometry));
    PetscFunctionReturn(0);
  }
};

template <int D>
PetscErrorCode Write(MPI_Comm comm, const std::array<int, D> &cells, const std::string &path, bool with_c33)
{
  PetscFunctionBegin;
  Box<D> b;
  PetscCall(b.Make(comm, cells));
  KnownState<D> known(b.box);
  known.header.geometry = b.geometry;
  PetscCall(WriteCheckpoint<D>(comm, path, b.order, b.box.local, &known.header, known.View(with_c33)));
  PetscFunctionReturn(0);
}

const std::array<int, 3> kCells3{9, 5, 4}; // 180 points, families of up to 97 members (2 mask words)
const std::array<int, 2> kCells2{14, 9};

class Checkpoint3D : public ::testing::Test {
protected:
  void SetUp() override
  {
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    MPI_Comm_size(PETSC_COMM_WORLD, &size);
  }
  // A communicator of the first n ranks (MPI_COMM_NULL on the others).
  MPI_Comm First(int n)
  {
    MPI_Comm comm;
    MPI_Comm_split(PETSC_COMM_WORLD, rank < n ? 0 : MPI_UNDEFINED, rank, &comm);
    return comm;
  }
  // Reads `path` on comm into a 3D box of its own and checks every value, exactly.
  void ReadBackExactly(MPI_Comm comm, const std::string &path, bool with_c33, int writers)
  {
    Box<3> b;
    ASSERT_EQ(b.Make(comm, kCells3), 0);
    KnownState<3>    expected(b.box);
    KnownState<3>    read(b.box);
    CheckpointHeader header;
    for (auto *v : {&read.u, &read.v, &read.relaxation_u, &read.relaxation_a, &read.eigenvector, &read.c33}) std::fill(v->begin(), v->end(), -1.0);
    std::fill(read.bonds.intact.begin(), read.bonds.intact.end(), 0);
    ASSERT_EQ(ReadCheckpointHeader(comm, path, &header), 0);
    EXPECT_EQ(header.dimension, 3);
    EXPECT_EQ(header.has_c33, with_c33);
    EXPECT_EQ(header.ranks, writers);
    EXPECT_EQ(header.step, 17);
    ASSERT_EQ(ReadCheckpointState<3>(comm, path, b.order, b.box.local, header, b.geometry, read.View(true)), 0);
    // Tolerance 0: a checkpoint restores the state bit for bit on any rank count.
    EXPECT_EQ(read.u, expected.u);
    EXPECT_EQ(read.v, expected.v);
    EXPECT_EQ(read.relaxation_u, expected.relaxation_u);
    EXPECT_EQ(read.relaxation_a, expected.relaxation_a);
    EXPECT_EQ(read.eigenvector, expected.eigenvector);
    EXPECT_EQ(read.bonds.intact, expected.bonds.intact); // owned and ring-1 points, as their owners have them
    // Without /bonds/c33 (none stored) every warm start is the cold start, 0.
    const std::vector<double> c33 = with_c33 ? expected.c33 : std::vector<double>(read.c33.size(), 0.0);
    EXPECT_EQ(read.c33, c33);
    std::size_t broken = read.bonds.count_broken(b.box.local, b.box.local.n_family);
    EXPECT_GT(broken, 0u); // the rule broke some bonds here
  }
  // The code and message of reading path into a box of dimension D on every rank.
  template <int D>
  std::string Refusal(const std::string &path, const std::array<int, D> &cells)
  {
    Box<D> b;
    EXPECT_EQ(b.Make(PETSC_COMM_WORLD, cells), 0);
    KnownState<D>    state(b.box);
    CheckpointHeader header;
    EXPECT_EQ(ReadCheckpointHeader(PETSC_COMM_WORLD, path, &header), 0);
    PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
    const PetscErrorCode code = ReadCheckpointState<D>(PETSC_COMM_WORLD, path, b.order, b.box.local, header, b.geometry, state.View(true));
    PetscPopErrorHandler();
    EXPECT_EQ(code, PETSC_ERR_USER);
    return bapd_test::LastErrorText();
  }
  // Rank 0 edits the root attributes of a file (then everyone reads it).
  void EditAttributes(const std::string &path, const std::function<void(hid_t)> &edit)
  {
    if (rank == 0) {
      const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
      ASSERT_GE(file, 0);
      const hid_t root = H5Gopen2(file, "/", H5P_DEFAULT);
      edit(root);
      H5Gclose(root);
      H5Fclose(file);
    }
    MPI_Barrier(PETSC_COMM_WORLD);
  }
  int rank = 0, size = 1;
};

void SetInt64(hid_t object, const char *name, std::int64_t value)
{
  const hid_t attribute = H5Aopen(object, name, H5P_DEFAULT);
  H5Awrite(attribute, H5T_NATIVE_INT64, &value);
  H5Aclose(attribute);
}

TEST_F(Checkpoint3D, WrittenOnTwoRanksReadsBackExactlyOnOneAndOnAll)
{
  const int  writers = std::min(size, 2);
  MPI_Comm   two     = First(writers);
  for (bool with_c33 : {true, false}) {
    const std::string path = with_c33 ? "checkpoint_3d_test.h5" : "checkpoint_3d_no_c33_test.h5";
    if (two != MPI_COMM_NULL) {
      ASSERT_EQ(Write<3>(two, kCells3, path, with_c33), 0);
    }
    MPI_Barrier(PETSC_COMM_WORLD);
    if (rank == 0) {
      // The file's own view: D-vector datasets of 3 columns, C33 only when written.
      const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
      ASSERT_GE(file, 0);
      for (const char *name : {"/points/displacement", "/points/velocity", "/relaxation/displacement", "/time_step/eigenvector"}) {
        const hid_t set = H5Dopen2(file, name, H5P_DEFAULT), space = H5Dget_space(set);
        hsize_t     dims[2] = {0, 0};
        EXPECT_EQ(H5Sget_simple_extent_ndims(space), 2) << name;
        H5Sget_simple_extent_dims(space, dims, nullptr);
        EXPECT_EQ(dims[0], 180u) << name;
        EXPECT_EQ(dims[1], 3u) << name;
        H5Sclose(space), H5Dclose(set);
      }
      EXPECT_EQ(H5Lexists(file, "/bonds/c33", H5P_DEFAULT) > 0, with_c33);
      H5Fclose(file);
    }
    MPI_Comm one = First(1);
    if (one != MPI_COMM_NULL) ReadBackExactly(one, path, with_c33, writers);
    ReadBackExactly(PETSC_COMM_WORLD, path, with_c33, writers);
    if (one != MPI_COMM_NULL) MPI_Comm_free(&one);
  }
  if (two != MPI_COMM_NULL) MPI_Comm_free(&two);
}

TEST_F(Checkpoint3D, ACheckpointContinuesOnlyInItsOwnDimension)
{
  ASSERT_EQ(Write<3>(PETSC_COMM_WORLD, kCells3, "checkpoint_3d_dimension.h5", true), 0);
  ASSERT_EQ(Write<2>(PETSC_COMM_WORLD, kCells2, "checkpoint_2d_dimension.h5", true), 0);
  const std::string as_2d = Refusal<2>("checkpoint_3d_dimension.h5", kCells2);
  EXPECT_NE(as_2d.find("Checkpoint 'checkpoint_3d_dimension.h5' holds a 3D body and this scene is 2D"), std::string::npos) << as_2d;
  const std::string as_3d = Refusal<3>("checkpoint_2d_dimension.h5", kCells3);
  EXPECT_NE(as_3d.find("Checkpoint 'checkpoint_2d_dimension.h5' holds a 2D body and this scene is 3D"), std::string::npos) << as_3d;
}

TEST_F(Checkpoint3D, AFileOfFormat5ReadsAs2D)
{
  // Format 5 had no dimension attribute; its arrays are those of a 2D format 6 file.
  const std::string path = "checkpoint_format5.h5";
  ASSERT_EQ(Write<2>(PETSC_COMM_WORLD, kCells2, path, true), 0);
  EditAttributes(path, [](hid_t root) {
    H5Adelete(root, "dimension");
    SetInt64(root, "format_version", 5);
  });
  Box<2> b;
  ASSERT_EQ(b.Make(PETSC_COMM_WORLD, kCells2), 0);
  KnownState<2>    expected(b.box), read(b.box);
  CheckpointHeader header;
  std::fill(read.u.begin(), read.u.end(), 0.0);
  ASSERT_EQ(ReadCheckpointHeader(PETSC_COMM_WORLD, path, &header), 0);
  EXPECT_EQ(header.format_version, 5);
  EXPECT_EQ(header.dimension, 2);
  ASSERT_EQ(ReadCheckpointState<2>(PETSC_COMM_WORLD, path, b.order, b.box.local, header, b.geometry, read.View(true)), 0);
  EXPECT_EQ(read.u, expected.u);
  EXPECT_EQ(read.c33, expected.c33);
}

TEST_F(Checkpoint3D, ADamagedDimensionIsRefused)
{
  const std::string missing = "checkpoint_no_dimension.h5", wrong = "checkpoint_dimension_4.h5";
  ASSERT_EQ(Write<3>(PETSC_COMM_WORLD, kCells3, missing, true), 0);
  ASSERT_EQ(Write<3>(PETSC_COMM_WORLD, kCells3, wrong, true), 0);
  EditAttributes(missing, [](hid_t root) { H5Adelete(root, "dimension"); });
  EditAttributes(wrong, [](hid_t root) { SetInt64(root, "dimension", 4); });
  const struct {
    std::string path, says;
  } cases[] = {{missing, "is damaged: attribute dimension is missing"}, {wrong, "is damaged: attribute dimension is 4, not 2 or 3"}};
  for (const auto &c : cases) {
    CheckpointHeader header;
    PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
    const PetscErrorCode code = ReadCheckpointHeader(PETSC_COMM_WORLD, c.path, &header);
    PetscPopErrorHandler();
    EXPECT_EQ(code, PETSC_ERR_FILE_UNEXPECTED);
    const char *generic  = nullptr;
    char       *specific = nullptr;
    PetscErrorMessage(code, &generic, &specific);
    const std::string text = specific ? specific : "";
    EXPECT_NE(text.find(c.says), std::string::npos) << text;
  }
}

} // namespace
