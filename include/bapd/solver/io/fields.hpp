#pragma once
// Field output: point clouds over time for ParaView and scripts. docs/options.md,
// "Output", is the user's view.
//
// Every -output_fields_interval steps one HDF5 file <output_dir>/fields/step_NNNNNNNN.h5
// holds, in natural-id order (natural_order.hpp; the same file on any rank layout
// except /rank). Vectors have 3 components and tensors 9 (row-major 3x3) because XDMF's
// do: a body of dimension D (2 or 3) fills the first D components of a vector and the
// D x D block of a tensor; in 2D the out-of-plane ones are 0 unless said.
//   /natural_id            (points)    -     the point's lattice index (= the row); also
//                                            the Polyvertex connectivity of the XDMF
//   /rank                  (points)    -     the rank that owned the point (int32)
//   /reference_position    (points, 3) m     x, y, z (z = 0 in 2D)
//   /position              (points, 3) m     current position x + u
//   /displacement          (points, 3) m
//   /velocity              (points, 3) m/s
//   /volume                (points)    m^3   V_i (dx^2 thickness on a 2D lattice, dx^3 in 3D)
//   /force_density         (points, 3) N/m^3 internal force density f_i (eq 1)
//   /damage                (points)    -     eq 38: 1 - intact family volume / V(H_i)
//   /max_bond_stretch      (points)    -     largest |y_j - y_i| / |x_j - x_i| over the
//                                            point's intact bonds (0 if none is left);
//                                            a bond breaks past -failure_critical_stretch
//   /nominal_stress        (points, 9) Pa    P_i, mean of the bond-associated P(F_ij)
//                                            with the force's weights (point_quantities.hpp)
//   /cauchy_stress         (points, 9) Pa    sigma_i = P_i F_i^T / J_i
//   /deformation_gradient  (points, 9) -     F_i (same weights); 2D: F_33 = lambda_3
//   /thickness_stretch     (points)    -     2D only: lambda_3 = sqrt(C33) (plane stress;
//                                            1 in plane strain)
//   /strain_energy_density (points)    J/m^3 W_i (sum V_i W_i is history.csv's internal energy)
//   /von_mises_stress      (points)    Pa    sqrt(3/2 s : s), s the deviator of sym(sigma_i)
//                                            (2D: sigma_33 = 0; derived_fields.hpp)
//   /principal_stretch     (points, 3) -     eigenvalues of sqrt(F_i^T F_i): 2D the two
//                                            in-plane ones, largest first, then lambda_3;
//                                            3D all three, largest first
// with attributes step, time_s, stretch (the applied lambda) and dimension (D).
// <output_dir>/fields.xdmf lists the files as a time series of Polyvertex point clouds
// with an explicit connectivity (every ParaView reader then makes one cell per point),
// the run state (time_s, step, stretch) as one-value Grid attributes (ParaView's field
// data), and the current or the reference positions as the XYZ geometry
// (-output_fields_geometry).
//
// D is a template parameter of what reads D-vectors or lists the datasets of a D
// (largest_bond_stretch, WriteFieldFrame, WriteFieldIndex), instantiated for 2 and 3.
#include <petscsys.h>

#include <string>
#include <vector>

#include "bapd/core/geometry/body.hpp"
#include "bapd/core/kernel/bond_state.hpp"
#include "bapd/core/geometry/family.hpp"
#include "bapd/solver/input/scene_output.hpp"
#include "bapd/solver/parallel/natural_order.hpp"

namespace bapd {

struct FieldFrame {
  PetscInt step    = 0;
  double   time    = 0;
  double   stretch = -1; // < 0: not known here (a frame listed again on restart): read from its file
};

// The files written so far and where they go.
struct FieldSeries {
  std::string             output_dir;
  FieldGeometry           geometry = FieldGeometry::current;
  std::vector<FieldFrame> frames;
  std::vector<double>     reference; // this rank's natural block, D per point (set on the first write)
};

// The point arrays of a field file, after natural_id, rank, reference_position and
// position, in the order of the file and of fields.xdmf: X(name, shape), shape the
// numbers a point holds (scalar 1, vector D, tensor D x D, triple 3 in 2D and 3D). The
// name is the dataset's and PointFields' member's. A new output field is one row here
// plus its computation where the driver fills PointFields (simulation_output.cpp); its
// dataset, its exchange to natural order and its XDMF attribute follow from the row.
//   thickness_stretch: lambda_3, 2D only (no dataset in 3D)
//   load_set: 0 free, k held by the scene's k-th load set
#define BAPD_POINT_FIELDS(X)       \
  X(displacement, vector)          \
  X(velocity, vector)              \
  X(volume, scalar)                \
  X(force_density, vector)         \
  X(damage, scalar)                \
  X(max_bond_stretch, scalar)      \
  X(nominal_stress, tensor)        \
  X(cauchy_stress, tensor)         \
  X(deformation_gradient, tensor)  \
  X(thickness_stretch, scalar)     \
  X(strain_energy_density, scalar) \
  X(von_mises_stress, scalar)      \
  X(principal_stretch, triple)     \
  X(load_set, scalar)

// The fields of the owned points, in local order; a D-vector has D numbers a point, a
// tensor D x D (row-major: xx, xy, yx, yy in 2D), as point_quantities.hpp forms them.
struct PointFields {
  const double *reference = nullptr; // D per point
#define BAPD_POINT_FIELD_MEMBER(name, shape) const double *name = nullptr;
  BAPD_POINT_FIELDS(BAPD_POINT_FIELD_MEMBER)
#undef BAPD_POINT_FIELD_MEMBER
};

// Largest stretch over the intact bonds of points [0, n) (y: current positions of
// the local points, D a point); 0 for a point whose bonds are all broken.
template <int D>
void largest_bond_stretch(const PointCloud &cloud, const double *y, const Families &families, const BondState &state,
                          std::size_t n, double *stretch);

// Collective. Writes the file of this step and rewrites fields.xdmf (rank 0).
template <int D>
PetscErrorCode WriteFieldFrame(MPI_Comm comm, const NaturalOrder &order, FieldSeries *series, PetscInt step, double time,
                               double stretch, const PointFields &fields);
// Rank 0: fields.xdmf listing series.frames (written to a temporary name, renamed),
// with the datasets a file of dimension D holds.
template <int D>
PetscErrorCode WriteFieldIndex(MPI_Comm comm, const FieldSeries &series, PetscInt n_points);
// The file of a step, relative to the output directory.
std::string FieldFileName(PetscInt step);

} // namespace bapd
