// Field output: HDF5 point data in natural order plus an XDMF index (fields.hpp).
#include "bapd/fields.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "bapd/hdf5_io.hpp"
#include "bapd/scene.hpp"

namespace bapd {

PetscErrorCode FieldOptionsFromOptions(MPI_Comm comm, FieldOptions *options)
{
  PetscFunctionBegin;
  for (const char *name : {"-output_fields", "-output_fields_interval"}) RegisterOptionName(name);
  PetscOptionsBegin(comm, nullptr, "Field output (HDF5 + XDMF for ParaView)", "bapd");
  PetscCall(PetscOptionsBool("-output_fields", "Write the point fields (<output_dir>/fields/*.h5 and fields.xdmf)", "docs/options.md",
                             options->enabled, &options->enabled, nullptr));
  PetscCall(PetscOptionsInt("-output_fields_interval", "Time steps between field files [-]; 0: about 20 a run", "docs/options.md",
                            options->interval, &options->interval, nullptr));
  PetscOptionsEnd();
  PetscCheck(options->interval >= 0, comm, PETSC_ERR_USER, "-output_fields_interval %" PetscInt_FMT ": give a number of steps >= 1 (or 0 for about 20 files a run)",
             options->interval);
  PetscFunctionReturn(0);
}

void largest_bond_stretch(const PointCloud &cloud, const double *y, const Families &families, const BondState &state,
                          std::size_t n, double *stretch)
{
  const double *x = cloud.x.data();
  for (std::size_t i = 0; i < n; ++i) {
    double largest2 = 0.0; // of the squared stretch: one square root per point
    for (std::size_t b = families.offsets[i]; b < families.offsets[i + 1]; ++b) {
      if (!state.is_intact(i, b - families.offsets[i])) continue;
      const std::size_t j  = (std::size_t)families.neighbour[b];
      const double      ex = y[2 * j] - y[2 * i], ey = y[2 * j + 1] - y[2 * i + 1];
      const double      rx = x[2 * j] - x[2 * i], ry = x[2 * j + 1] - x[2 * i + 1];
      largest2             = std::max(largest2, (ex * ex + ey * ey) / (rx * rx + ry * ry));
    }
    stretch[i] = std::sqrt(largest2);
  }
}

std::string FieldFileName(PetscInt step)
{
  char name[64];
  std::snprintf(name, sizeof name, "fields/step_%08lld.h5", (long long)step);
  return name;
}

PetscErrorCode WriteFieldFrame(MPI_Comm comm, const NaturalOrder &order, FieldSeries *series, PetscInt step, double time,
                               double stretch, const PointFields &fields)
{
  PetscMPIInt  rank;
  MPI_Datatype unit;
  PetscInt     owned;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscSFGetGraph(order.owned_points, nullptr, &owned, nullptr, nullptr));
  int ok = 1;
  if (rank == 0) {
    std::error_code ec;
    std::filesystem::create_directories(series->output_dir + "/fields", ec);
    ok = !ec;
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, comm));
  PetscCheck(ok, comm, PETSC_ERR_FILE_OPEN, "Cannot create %s/fields: choose a writable -output_dir", series->output_dir.c_str());

  // Owned points -> natural block, 6 numbers per point in one exchange (the
  // reference positions once per run).
  const PetscInt      count = order.point_count;
  std::vector<double> local(6 * owned), block(6 * count);
  for (PetscInt i = 0; i < owned; ++i) {
    local[6 * i]     = fields.displacement[2 * i];
    local[6 * i + 1] = fields.displacement[2 * i + 1];
    local[6 * i + 2] = fields.velocity[2 * i];
    local[6 * i + 3] = fields.velocity[2 * i + 1];
    local[6 * i + 4] = fields.damage[i];
    local[6 * i + 5] = fields.max_bond_stretch[i];
  }
  PetscCallMPI(MPI_Type_contiguous(6, MPI_DOUBLE, &unit));
  PetscCallMPI(MPI_Type_commit(&unit));
  PetscCall(ToNaturalOrder(order.owned_points, unit, local.data(), block.data()));
  PetscCallMPI(MPI_Type_free(&unit));
  if (series->reference.size() != (std::size_t)(2 * count)) {
    series->reference.assign(2 * count, 0.0);
    PetscCallMPI(MPI_Type_contiguous(2, MPI_DOUBLE, &unit));
    PetscCallMPI(MPI_Type_commit(&unit));
    PetscCall(ToNaturalOrder(order.owned_points, unit, fields.reference, series->reference.data()));
    PetscCallMPI(MPI_Type_free(&unit));
  }
  std::vector<double> reference(3 * count), position(3 * count), u(3 * count), v(3 * count), damage(count), largest(count);
  for (PetscInt k = 0; k < count; ++k) {
    for (int c = 0; c < 2; ++c) {
      reference[3 * k + c] = series->reference[2 * k + c];
      u[3 * k + c]         = block[6 * k + c];
      v[3 * k + c]         = block[6 * k + 2 + c];
      position[3 * k + c]  = reference[3 * k + c] + u[3 * k + c];
    }
    reference[3 * k + 2] = position[3 * k + 2] = u[3 * k + 2] = v[3 * k + 2] = 0.0;
    damage[k]                                                             = block[6 * k + 4];
    largest[k]                                                            = block[6 * k + 5];
  }

  const std::string path = series->output_dir + "/" + FieldFileName(step);
  const hsize_t     N = (hsize_t)order.n_points, start = (hsize_t)order.point_start, n = (hsize_t)count;
  {
    H5ParallelFile f;
    PetscCall(f.Create(comm, path));
    PetscCall(f.WriteAttribute("/", "format", std::string("bapd fields")));
    PetscCall(f.WriteAttribute("/", "format_version", (std::int64_t)1));
    PetscCall(f.WriteAttribute("/", "step", (std::int64_t)step));
    PetscCall(f.WriteAttribute("/", "time_s", time));
    PetscCall(f.WriteAttribute("/", "stretch", stretch));
    PetscCall(f.WriteBlock("/reference_position", H5T_NATIVE_DOUBLE, N, 3, start, n, reference.data()));
    PetscCall(f.WriteBlock("/position", H5T_NATIVE_DOUBLE, N, 3, start, n, position.data()));
    PetscCall(f.WriteBlock("/displacement", H5T_NATIVE_DOUBLE, N, 3, start, n, u.data()));
    PetscCall(f.WriteBlock("/velocity", H5T_NATIVE_DOUBLE, N, 3, start, n, v.data()));
    PetscCall(f.WriteBlock("/damage", H5T_NATIVE_DOUBLE, N, 0, start, n, damage.data()));
    PetscCall(f.WriteBlock("/max_bond_stretch", H5T_NATIVE_DOUBLE, N, 0, start, n, largest.data()));
    PetscCall(f.Close());
  }
  while (!series->frames.empty() && series->frames.back().step >= step) series->frames.pop_back();
  series->frames.push_back({step, time});
  PetscCall(WriteFieldIndex(comm, *series, order.n_points));
  PetscFunctionReturn(0);
}

PetscErrorCode WriteFieldIndex(MPI_Comm comm, const FieldSeries &series, PetscInt n_points)
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  int ok = 1;
  if (rank == 0) {
    const std::string path = series.output_dir + "/fields.xdmf", tmp = path + ".tmp";
    FILE             *f    = std::fopen(tmp.c_str(), "w");
    ok                     = f != nullptr;
    if (f) {
      const long long N = (long long)n_points;
      std::fprintf(f, "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"2.0\">\n <Domain>\n");
      std::fprintf(f, "  <Grid Name=\"bapd\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
      for (const FieldFrame &frame : series.frames) {
        const std::string file = FieldFileName(frame.step);
        auto item = [&](const char *dataset, int components) {
          if (components > 1)
            std::fprintf(f, "     <DataItem Dimensions=\"%lld %d\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/%s</DataItem>\n",
                         N, components, file.c_str(), dataset);
          else
            std::fprintf(f, "     <DataItem Dimensions=\"%lld\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/%s</DataItem>\n",
                         N, file.c_str(), dataset);
        };
        std::fprintf(f, "   <Grid Name=\"step %lld\" GridType=\"Uniform\">\n", (long long)frame.step);
        std::fprintf(f, "    <Time Value=\"%.17g\"/>\n", frame.time);
        std::fprintf(f, "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%lld\" NodesPerElement=\"1\"/>\n", N);
        std::fprintf(f, "    <Geometry GeometryType=\"XYZ\">\n");
        item("position", 3);
        std::fprintf(f, "    </Geometry>\n");
        for (const char *name : {"displacement", "velocity", "reference_position"}) {
          std::fprintf(f, "    <Attribute Name=\"%s\" AttributeType=\"Vector\" Center=\"Node\">\n", name);
          item(name, 3);
          std::fprintf(f, "    </Attribute>\n");
        }
        for (const char *name : {"damage", "max_bond_stretch"}) {
          std::fprintf(f, "    <Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"Node\">\n", name);
          item(name, 1);
          std::fprintf(f, "    </Attribute>\n");
        }
        std::fprintf(f, "   </Grid>\n");
      }
      std::fprintf(f, "  </Grid>\n </Domain>\n</Xdmf>\n");
      ok = std::fclose(f) == 0 && std::rename(tmp.c_str(), path.c_str()) == 0;
    }
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, comm));
  PetscCheck(ok, comm, PETSC_ERR_FILE_WRITE, "Cannot write %s/fields.xdmf: choose a writable -output_dir", series.output_dir.c_str());
  PetscFunctionReturn(0);
}

} // namespace bapd
