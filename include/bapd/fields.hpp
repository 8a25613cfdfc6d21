#pragma once
// Field output: point clouds over time for ParaView and scripts (STYLE.md: ... ->
// fields). docs/options.md, "Field output", is the user's view.
//
// Every -output_fields_interval steps one HDF5 file <output_dir>/fields/step_NNNNNNNN.h5
// holds, in natural-id order (natural_order.hpp; the same file on any rank layout):
//   /reference_position (points, 3) m     x, y, 0 (3 components: XDMF vectors have 3)
//   /position           (points, 3) m     current position x + u
//   /displacement       (points, 3) m
//   /velocity           (points, 3) m/s
//   /damage             (points)    -     eq 38: 1 - intact family volume / V(H_i)
//   /max_bond_stretch   (points)    -     largest |y_j - y_i| / |x_j - x_i| over the
//                                         point's intact bonds (0 if none is left);
//                                         a bond breaks past -failure_critical_stretch
// with attributes step, time_s, stretch (the applied lambda). <output_dir>/fields.xdmf
// lists the files as a time series of Polyvertex point clouds at the current positions.
#include <petscsys.h>

#include <string>
#include <vector>

#include "bapd/body.hpp"
#include "bapd/bond_state.hpp"
#include "bapd/family.hpp"
#include "bapd/natural_order.hpp"

namespace bapd {

// -output_fields, -output_fields_interval.
struct FieldOptions {
  PetscBool enabled  = PETSC_FALSE;
  PetscInt  interval = 0; // steps between files; 0: about 20 files a run
};
PetscErrorCode FieldOptionsFromOptions(MPI_Comm comm, FieldOptions *options);

struct FieldFrame {
  PetscInt step = 0;
  double   time = 0;
};

// The files written so far and where they go.
struct FieldSeries {
  std::string             output_dir;
  std::vector<FieldFrame> frames;
  std::vector<double>     reference; // this rank's natural block, 2 per point (set on the first write)
};

// The fields of the owned points, in local order.
struct PointFields {
  const double *reference        = nullptr; // 2 per point
  const double *displacement     = nullptr; // 2 per point
  const double *velocity         = nullptr; // 2 per point
  const double *damage           = nullptr; // 1 per point
  const double *max_bond_stretch = nullptr; // 1 per point
};

// Largest stretch over the intact bonds of points [0, n) (y: current positions of
// the local points); 0 for a point whose bonds are all broken.
void largest_bond_stretch(const PointCloud &cloud, const double *y, const Families &families, const BondState &state,
                          std::size_t n, double *stretch);

// Collective. Writes the file of this step and rewrites fields.xdmf (rank 0).
PetscErrorCode WriteFieldFrame(MPI_Comm comm, const NaturalOrder &order, FieldSeries *series, PetscInt step, double time,
                               double stretch, const PointFields &fields);
// Rank 0: fields.xdmf listing series.frames (written to a temporary name, renamed).
PetscErrorCode WriteFieldIndex(MPI_Comm comm, const FieldSeries &series, PetscInt n_points);
// The file of a step, relative to the output directory.
std::string FieldFileName(PetscInt step);

} // namespace bapd
