// Field files in 3D: a 3D state written as a field file on any
// number of ranks holds, in natural order, the three components of every vector and the
// full 3 x 3 of every tensor, exactly as given, and no thickness stretch (a 2D
// quantity); fields.xdmf draws it with XYZ geometry. The largest bond stretch of a 3D
// affine stretch is its largest principal stretch.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "bapd/solver/io/fields.hpp"
#include "bapd/solver/parallel/natural_order.hpp"
#include "mpi/box_layout.hpp"

using namespace bapd;
using bapd_test::BoxLayout;
using bapd_test::PointValue;

namespace {

enum Tag { kU = 1, kV, kForce, kNominal, kCauchy, kDeformation, kScalar };

// A dataset of a field file, read whole (rank 0); shape in dims.
std::vector<double> ReadDataset(hid_t file, const char *name, std::vector<hsize_t> *dims)
{
  const hid_t set = H5Dopen2(file, name, H5P_DEFAULT), space = H5Dget_space(set);
  dims->assign(H5Sget_simple_extent_ndims(space), 0);
  H5Sget_simple_extent_dims(space, dims->data(), nullptr);
  hsize_t n = 1;
  for (hsize_t d : *dims) n *= d;
  std::vector<double> values(n);
  H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Sclose(space);
  H5Dclose(set);
  return values;
}

// The XDMF of the frame written in output_dir: XYZ geometry from the (points, 3)
// positions, 3-vectors and 3 x 3 tensors, and no thickness stretch.
void ExpectXdmfDrawsXYZ(const std::string &output_dir)
{
  std::ifstream      in(output_dir + "/fields.xdmf");
  std::ostringstream text;
  text << in.rdbuf();
  const std::string xdmf = text.str();
  EXPECT_NE(xdmf.find("<Geometry GeometryType=\"XYZ\">\n     <DataItem Dimensions=\"120 3\" NumberType=\"Float\" Precision=\"8\" "
                      "Format=\"HDF\">fields/step_00000005.h5:/position</DataItem>"),
            std::string::npos)
      << xdmf;
  EXPECT_NE(xdmf.find("<Attribute Name=\"displacement\" AttributeType=\"Vector\" Center=\"Node\">\n     <DataItem Dimensions=\"120 3\""),
            std::string::npos);
  EXPECT_NE(xdmf.find("<Attribute Name=\"deformation_gradient\" AttributeType=\"Tensor\" Center=\"Node\">\n     <DataItem Dimensions=\"120 9\""),
            std::string::npos);
  EXPECT_EQ(xdmf.find("thickness_stretch"), std::string::npos);
}

TEST(Fields3D, VectorsAndTensorsHoldAllThreeComponentsAndTheXdmfDrawsXYZ)
{
  PetscMPIInt rank, size;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  BoxLayout box;
  ASSERT_EQ(bapd_test::MakeBoxLayout<3>(PETSC_COMM_WORLD, {6, 5, 4}, 2.015, &box), 0);
  NaturalOrder order;
  ASSERT_EQ(NaturalOrderCreate(PETSC_COMM_WORLD, box.layout, box.local, &order), 0);
  const Layout &l = box.layout;
  const PetscInt n = l.n_owned;
  auto           values = [&](int per_point, int tag) {
    std::vector<double> out(per_point * n);
    for (PetscInt i = 0; i < n; ++i)
      for (int c = 0; c < per_point; ++c) out[per_point * i + c] = PointValue(l.cloud.natural_id[i], c, tag);
    return out;
  };
  const std::vector<double> u = values(3, kU), v = values(3, kV), force = values(3, kForce), nominal = values(9, kNominal),
                            cauchy = values(9, kCauchy), deformation = values(9, kDeformation), scalars = values(3, kScalar);
  std::vector<double> damage(n), stretch(n), energy(n);
  for (PetscInt i = 0; i < n; ++i) damage[i] = scalars[3 * i], stretch[i] = scalars[3 * i + 1], energy[i] = scalars[3 * i + 2];
  PointFields fields;
  fields.reference             = l.cloud.x.data();
  fields.displacement          = u.data();
  fields.velocity              = v.data();
  fields.force_density         = force.data();
  fields.nominal_stress        = nominal.data();
  fields.cauchy_stress         = cauchy.data();
  fields.deformation_gradient  = deformation.data();
  fields.damage                = damage.data();
  fields.max_bond_stretch      = stretch.data();
  fields.strain_energy_density = energy.data();
  fields.volume                = l.cloud.volume.data();
  FieldSeries series;
  series.output_dir = "fields_3d_test_np" + std::to_string(size);
  if (rank == 0) {
    std::filesystem::remove_all(series.output_dir);
    std::filesystem::create_directories(series.output_dir);
  }
  MPI_Barrier(PETSC_COMM_WORLD);
  ASSERT_EQ(WriteFieldFrame<3>(PETSC_COMM_WORLD, order, &series, 5, 0.5, 1.25, fields), 0);
  if (rank != 0) return;

  const std::size_t N    = 120;
  const hid_t       file = H5Fopen((series.output_dir + "/" + FieldFileName(5)).c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  std::int64_t dimension = 0;
  {
    const hid_t attribute = H5Aopen(file, "dimension", H5P_DEFAULT);
    H5Aread(attribute, H5T_NATIVE_INT64, &dimension);
    H5Aclose(attribute);
  }
  EXPECT_EQ(dimension, 3);
  EXPECT_EQ(H5Lexists(file, "/thickness_stretch", H5P_DEFAULT), 0); // a 2D quantity
  std::vector<hsize_t> dims;
  // Vectors (points, 3) and tensors (points, 9, the full 3 x 3 row-major): every
  // component the point's (natural id = row), exactly.
  const struct {
    const char *name;
    int         tag;
    hsize_t     columns;
  } arrays[] = {{"/displacement", kU, 3},       {"/velocity", kV, 3},           {"/force_density", kForce, 3},
                {"/nominal_stress", kNominal, 9}, {"/cauchy_stress", kCauchy, 9}, {"/deformation_gradient", kDeformation, 9}};
  for (const auto &array : arrays) {
    const std::vector<double> data = ReadDataset(file, array.name, &dims);
    ASSERT_EQ(dims, (std::vector<hsize_t>{N, array.columns})) << array.name;
    for (std::size_t k = 0; k < N; ++k)
      for (int c = 0; c < (int)array.columns; ++c)
        ASSERT_EQ(data[array.columns * k + c], PointValue((std::int64_t)k, c, array.tag)) << array.name << " row " << k;
  }
  const std::vector<double> reference = ReadDataset(file, "/reference_position", &dims);
  ASSERT_EQ(dims, (std::vector<hsize_t>{N, 3}));
  const std::vector<double> position = ReadDataset(file, "/position", &dims);
  ASSERT_EQ(dims, (std::vector<hsize_t>{N, 3}));
  for (std::size_t k = 0; k < N; ++k)
    for (int d = 0; d < 3; ++d) {
      ASSERT_EQ(reference[3 * k + d], box.global.x[3 * k + d]);
      ASSERT_EQ(position[3 * k + d], box.global.x[3 * k + d] + PointValue((std::int64_t)k, d, kU));
    }
  const struct {
    const char *name;
    int         c;
  } scalar_sets[] = {{"/damage", 0}, {"/max_bond_stretch", 1}, {"/strain_energy_density", 2}};
  for (const auto &sc : scalar_sets) {
    const std::vector<double> data = ReadDataset(file, sc.name, &dims);
    ASSERT_EQ(dims, (std::vector<hsize_t>{N})) << sc.name;
    for (std::size_t k = 0; k < N; ++k) ASSERT_EQ(data[k], PointValue((std::int64_t)k, sc.c, kScalar)) << sc.name;
  }
  H5Fclose(file);

  ExpectXdmfDrawsXYZ(series.output_dir);
}

TEST(Fields3D, LargestBondStretchOfAnAffineStretchIsItsLargestPrincipalStretch)
{
  // y = diag(1.1, 1.05, 1.02) x: a bond's stretch is |A e| / |e|, largest (1.1) for the
  // bonds along x, which every point of a box 6 cells long in x has; to round-off.
  BoxLayout box;
  ASSERT_EQ(bapd_test::MakeBoxLayout<3>(PETSC_COMM_WORLD, {6, 5, 4}, 2.015, &box), 0);
  const Layout       &l = box.layout;
  const double        a[3] = {1.1, 1.05, 1.02};
  std::vector<double> y(l.cloud.x.size());
  for (std::size_t k = 0; k < y.size(); ++k) y[k] = a[k % 3] * l.cloud.x[k];
  BondState           intact(box.local);
  std::vector<double> stretch(l.n_owned);
  largest_bond_stretch<3>(l.cloud, y.data(), box.local, intact, (std::size_t)l.n_owned, stretch.data());
  // Round-off: y_j - y_i from two rounded products, relative error ~1e-15 at |x_j - x_i| = dx.
  for (double s : stretch) EXPECT_NEAR(s, 1.1, 1e-14);
  // Every bond broken: 0.
  std::fill(intact.intact.begin(), intact.intact.end(), 0);
  largest_bond_stretch<3>(l.cloud, y.data(), box.local, intact, (std::size_t)l.n_owned, stretch.data());
  for (double s : stretch) EXPECT_EQ(s, 0.0);
}

} // namespace
