// Field output: HDF5 point data in natural order plus an XDMF index (fields.hpp).
#include "bapd/solver/io/fields.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "bapd/solver/io/hdf5_io.hpp"
#include "bapd/solver/io/output_directory.hpp"
#include "bapd/solver/input/scene.hpp"

namespace bapd {

namespace {

// 1, 3, 9 components in the file; a triple is 3 numbers in any D (the principal
// stretches: 2D has an out-of-plane one), drawn as a vector.
enum class Shape { scalar, vector, tensor, triple };
int components(Shape s) { return s == Shape::scalar ? 1 : s == Shape::tensor ? 9 : 3; }
// Numbers a point holds in D dimensions: 1, D, D x D, 3.
template <int D> int width(Shape s) { return s == Shape::scalar ? 1 : s == Shape::vector ? D : s == Shape::tensor ? D * D : 3; }

// Where a dataset's values come from.
enum class Source {
  natural_id, // the point's natural id (int64)
  rank,       // the rank that owns the point (int32)
  reference,  // its reference position x (exchanged once a run)
  position,   // x + u
  point,      // an array of the owned points' PointFields (FieldArray::array)
};

// One dataset of a field file: the four of the points' identity and place, then a row
// of BAPD_POINT_FIELDS (fields.hpp) each.
struct FieldArray {
  const char *name;
  Shape       shape;
  Source      source;
  const double *PointFields::*array = nullptr; // Source::point: width<D>(shape) numbers a point
  bool        integer() const { return source == Source::natural_id || source == Source::rank; }
  int         precision() const { return source == Source::rank ? 4 : 8; } // int32 rank, else 8 bytes
  // lambda_3 is a 2D quantity (the thickness stretch of a sheet): no dataset in 3D.
  bool        in_dimension(int D) const { return array != &PointFields::thickness_stretch || D == 2; }
};
// The datasets of a field file, in the order the XDMF lists them.
constexpr FieldArray kArrays[] = {
    {"natural_id", Shape::scalar, Source::natural_id},
    {"rank", Shape::scalar, Source::rank},
    {"reference_position", Shape::vector, Source::reference},
    {"position", Shape::vector, Source::position},
#define BAPD_POINT_FIELD_ROW(name, shape) {#name, Shape::shape, Source::point, &PointFields::name},
    BAPD_POINT_FIELDS(BAPD_POINT_FIELD_ROW)
#undef BAPD_POINT_FIELD_ROW
};
constexpr std::size_t kArrayCount = sizeof kArrays / sizeof kArrays[0];

std::size_t ArrayIndex(const char *name)
{
  for (std::size_t k = 0; k < kArrayCount; ++k)
    if (std::string(kArrays[k].name) == name) return k;
  return 0; // (every caller names one of the table)
}
const FieldArray &Array(const char *name) { return kArrays[ArrayIndex(name)]; }

// One owned point's numbers, sent to the natural block in one exchange: the point
// arrays of kArrays in its order (width<D> numbers each), then the owner's rank.
template <int D> struct PackedRow {
  std::size_t offset[kArrayCount] = {}; // where array k starts in the row (Source::point)
  std::size_t rank = 0, size = 0;
  PackedRow()
  {
    for (std::size_t k = 0; k < kArrayCount; ++k)
      if (kArrays[k].source == Source::point) offset[k] = rank, rank += (std::size_t)width<D>(kArrays[k].shape);
    size = rank + 1;
  }
  std::size_t of(const char *name) const { return offset[ArrayIndex(name)]; }
};

// The dataset of a floating-point array from the natural block (PackedRow<D>::size per
// point): D components of a vector, the D x D block of a row-major 3x3 tensor, the rest 0.
template <int D>
void FromBlock(const FieldArray &a, const std::vector<double> &block, const std::vector<double> &reference, PetscInt count,
               std::vector<double> &out)
{
  const PackedRow<D> P;
  const int          c      = components(a.shape);
  const std::size_t  source = P.offset[&a - kArrays], displacement = P.of("displacement");
  const bool         moving = a.source == Source::position;
  out.assign((std::size_t)(c * count), 0.0);
  for (PetscInt k = 0; k < count; ++k) {
    const double *row = block.data() + P.size * k;
    double       *o   = out.data() + c * k;
    if (a.source == Source::reference || moving) {
      for (int d = 0; d < D; ++d) o[d] = reference[D * k + d] + (moving ? row[displacement + d] : 0.0);
    } else if (a.shape == Shape::scalar) {
      o[0] = row[source];
    } else if (a.shape == Shape::vector) {
      for (int d = 0; d < D; ++d) o[d] = row[source + d];
    } else if (a.shape == Shape::triple) {
      for (int d = 0; d < 3; ++d) o[d] = row[source + d];
    } else {
      for (int r = 0; r < D; ++r)
        for (int q = 0; q < D; ++q) o[3 * r + q] = row[source + D * r + q];
      if (D == 2 && a.array == &PointFields::deformation_gradient) o[8] = row[P.of("thickness_stretch")]; // F_33 = lambda_3
    }
  }
}

// One owned point's numbers in the order of PackedRow<D>.
template <int D>
void Pack(const PackedRow<D> &P, const PointFields &fields, int rank, PetscInt i, double *row)
{
  for (std::size_t k = 0; k < kArrayCount; ++k) {
    if (kArrays[k].source != Source::point) continue;
    const double *values = fields.*kArrays[k].array;
    const int     w      = width<D>(kArrays[k].shape);
    for (int c = 0; c < w; ++c) row[P.offset[k] + c] = values ? values[w * i + c] : 1.0; // 3D: no lambda_3, never written
  }
  row[P.rank] = rank;
}

// The applied stretch of a frame listed again on restart (FieldFrame::stretch < 0):
// its file's attribute; false if the file cannot tell.
bool StretchFromFile(const std::string &path, double *stretch)
{
  H5Quiet     quiet;
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) return false;
  const bool ok = H5ReadAttribute(file, "/", "stretch", stretch);
  H5Fclose(file);
  return ok;
}

} // namespace

template <int D>
void largest_bond_stretch(const PointCloud &cloud, const double *y, const Families &families, const BondState &state,
                          std::size_t n, double *stretch)
{
  const double *x = cloud.x.data();
  for (std::size_t i = 0; i < n; ++i) {
    double largest2 = 0.0; // of the squared stretch: one square root per point
    for (std::size_t b = families.offsets[i]; b < families.offsets[i + 1]; ++b) {
      if (!state.is_intact(i, b - families.offsets[i])) continue;
      const std::size_t j = (std::size_t)families.neighbour[b];
      double            e2 = 0.0, r2 = 0.0; // |y_j - y_i|^2, |x_j - x_i|^2
      for (int d = 0; d < D; ++d) {
        const double e = y[D * j + d] - y[D * i + d], r = x[D * j + d] - x[D * i + d];
        e2 += e * e;
        r2 += r * r;
      }
      largest2 = std::max(largest2, e2 / r2);
    }
    stretch[i] = std::sqrt(largest2);
  }
}

std::string FieldFileName(PetscInt step) { return OutputPaths::FieldName((long long)step); }

template <int D>
PetscErrorCode WriteFieldFrame(MPI_Comm comm, const NaturalOrder &order, FieldSeries *series, PetscInt step, double time,
                               double stretch, const PointFields &fields)
{
  const PackedRow<D> P;
  PetscMPIInt        rank;
  PetscInt           owned;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscSFGetGraph(order.owned_points, nullptr, &owned, nullptr, nullptr));
  // The output directory exists from the start of the run (history.csv): one that
  // is gone was deleted, and recreating it would hide that the run's files are lost.
  int ok = 1, there = 1;
  if (rank == 0) {
    std::error_code ec;
    there = std::filesystem::is_directory(series->output_dir, ec);
    if (there) std::filesystem::create_directories(OutputPaths(series->output_dir).fields_folder(), ec);
    ok = !ec;
    if (!ok) there = std::filesystem::is_directory(series->output_dir, ec); // deleted meanwhile?
  }
  int status[2] = {there, ok};
  PetscCallMPI(MPI_Bcast(status, 2, MPI_INT, 0, comm));
  there = status[0], ok = status[1];
  PetscCheck(there, comm, PETSC_ERR_FILE_WRITE, "The output directory %s was deleted during the run: the run stops (its files are lost). Keep -output_dir until the run ends",
             series->output_dir.c_str());
  PetscCheck(ok, comm, PETSC_ERR_FILE_OPEN, "Cannot create %s/fields: choose a writable -output_dir", series->output_dir.c_str());

  // Owned points -> natural block, PackedRow<D>::size numbers per point in one exchange
  // (the reference positions once per run).
  const PetscInt      count = order.point_count;
  std::vector<double> local(P.size * owned), block(P.size * count);
  for (PetscInt i = 0; i < owned; ++i) Pack<D>(P, fields, rank, i, local.data() + P.size * i);
  PetscCall(DoublesToNaturalOrder(order.owned_points, (int)P.size, local.data(), block.data()));
  if (series->reference.size() != (std::size_t)(D * count)) {
    series->reference.assign(D * count, 0.0);
    PetscCall(DoublesToNaturalOrder(order.owned_points, D, fields.reference, series->reference.data()));
  }

  const std::string path = OutputPaths(series->output_dir).field_file(step);
  const hsize_t     N = (hsize_t)order.n_points, start = (hsize_t)order.point_start, n = (hsize_t)count;
  {
    // Its size: per point every array of kArrays (the file's components, precision()
    // bytes each); 22 datasets and attributes.
    hsize_t point_bytes = 0;
    for (const FieldArray &a : kArrays) point_bytes += (hsize_t)(a.precision() * components(a.shape));
    H5ParallelFile f;
    PetscCall(f.Create(comm, path, N * point_bytes, 26));
    PetscCall(f.WriteAttribute("/", "format", std::string("bapd fields")));
    PetscCall(f.WriteAttribute("/", "format_version", (std::int64_t)2));
    PetscCall(f.WriteAttribute("/", "step", (std::int64_t)step));
    PetscCall(f.WriteAttribute("/", "time_s", time));
    PetscCall(f.WriteAttribute("/", "stretch", stretch));
    PetscCall(f.WriteAttribute("/", "dimension", (std::int64_t)D));
    std::vector<double> data;
    for (const FieldArray &a : kArrays) {
      if (!a.in_dimension(D)) continue;
      const std::string name = std::string("/") + a.name;
      if (a.source == Source::natural_id) {
        std::vector<std::int64_t> id(count);
        for (PetscInt k = 0; k < count; ++k) id[k] = (std::int64_t)(order.point_start + k);
        PetscCall(f.WriteBlock(name.c_str(), H5T_NATIVE_INT64, N, 0, start, n, id.data()));
      } else if (a.source == Source::rank) {
        std::vector<std::int32_t> owner(count);
        for (PetscInt k = 0; k < count; ++k) owner[k] = (std::int32_t)block[P.size * k + P.rank];
        PetscCall(f.WriteBlock(name.c_str(), H5T_NATIVE_INT32, N, 0, start, n, owner.data()));
      } else {
        FromBlock<D>(a, block, series->reference, count, data);
        const int c = components(a.shape);
        PetscCall(f.WriteBlock(name.c_str(), H5T_NATIVE_DOUBLE, N, c > 1 ? (hsize_t)c : 0, start, n, data.data()));
      }
    }
    PetscCall(f.Close());
  }
  while (!series->frames.empty() && series->frames.back().step >= step) series->frames.pop_back();
  series->frames.push_back({step, time, stretch});
  PetscCall(WriteFieldIndex<D>(comm, *series, order.n_points));
  PetscFunctionReturn(0);
}

template <int D>
PetscErrorCode WriteFieldIndex(MPI_Comm comm, const FieldSeries &series, PetscInt n_points)
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  // [errno of a failed write, index of the first frame whose file is gone + 1]: a
  // frame whose file was deleted (the output directory removed during the run) is
  // not listed, and stops the run.
  int         status[2] = {0, 0};
  std::string gone;
  if (rank == 0) {
    std::vector<char> present(series.frames.size(), 1);
    for (std::size_t k = 0; k < series.frames.size(); ++k) {
      std::error_code ec;
      present[k] = std::filesystem::exists(OutputPaths(series.output_dir).field_file(series.frames[k].step), ec);
      if (!present[k] && !status[1]) status[1] = (int)k + 1;
    }
    const std::string path = OutputPaths(series.output_dir).field_index(), tmp = path + ".tmp";
    FILE             *f    = std::fopen(tmp.c_str(), "w");
    if (!f) status[0] = errno;
    if (f) {
      const long long   N        = (long long)n_points;
      const char *const geometry = series.geometry == FieldGeometry::reference ? "reference_position" : "position";
      std::fprintf(f, "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"2.0\">\n <Domain>\n");
      std::fprintf(f, "  <Grid Name=\"bapd\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
      for (const FieldFrame &frame : series.frames) {
        if (!present[&frame - series.frames.data()]) continue;
        const std::string file = FieldFileName(frame.step);
        auto item = [&](const FieldArray &a) {
          const int c = components(a.shape);
          std::fprintf(f, "     <DataItem Dimensions=\"%lld", N);
          if (c > 1) std::fprintf(f, " %d", c);
          std::fprintf(f, "\" NumberType=\"%s\" Precision=\"%d\" Format=\"HDF\">%s:/%s</DataItem>\n", a.integer() ? "Int" : "Float",
                       a.precision(), file.c_str(), a.name);
        };
        auto run_state = [&](const char *name, const char *type, const char *value) {
          std::fprintf(f, "    <Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"Grid\">\n", name);
          std::fprintf(f, "     <DataItem Dimensions=\"1\" NumberType=\"%s\" Precision=\"8\" Format=\"XML\">%s</DataItem>\n", type, value);
          std::fprintf(f, "    </Attribute>\n");
        };
        std::fprintf(f, "   <Grid Name=\"step %lld\" GridType=\"Uniform\">\n", (long long)frame.step);
        std::fprintf(f, "    <Time Value=\"%.17g\"/>\n", frame.time);
        // An explicit connectivity: without it Xdmf3ReaderS (ParaView's default)
        // makes no cells and the default views draw nothing.
        std::fprintf(f, "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%lld\" NodesPerElement=\"1\">\n", N);
        item(Array("natural_id"));
        std::fprintf(f, "    </Topology>\n    <Geometry GeometryType=\"XYZ\">\n");
        item(Array(geometry));
        std::fprintf(f, "    </Geometry>\n");
        // The run state as one value per grid: field data in both ParaView readers
        // (an XDMF <Information> is not shown by all of them).
        char value[64];
        std::snprintf(value, sizeof value, "%.17g", frame.time);
        run_state("time_s", "Float", value);
        std::snprintf(value, sizeof value, "%lld", (long long)frame.step);
        run_state("step", "Int", value);
        double stretch = frame.stretch;
        if (stretch >= 0 || StretchFromFile(OutputPaths(series.output_dir).file(file), &stretch)) {
          std::snprintf(value, sizeof value, "%.17g", stretch);
          run_state("stretch", "Float", value);
        }
        static const char *const type[] = {"Scalar", "Vector", "Tensor", "Vector"};
        for (const FieldArray &a : kArrays) {
          if (&a == &Array(geometry) || !a.in_dimension(D)) continue;
          std::fprintf(f, "    <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"Node\">\n", a.name, type[(int)a.shape]);
          item(a);
          std::fprintf(f, "    </Attribute>\n");
        }
        std::fprintf(f, "   </Grid>\n");
      }
      std::fprintf(f, "  </Grid>\n </Domain>\n</Xdmf>\n");
      // Every write checked: a full disk shows at the flush, or earlier as the error flag.
      if ((std::fflush(f) != 0 || std::ferror(f)) && !status[0]) status[0] = errno ? errno : EIO;
      if (std::fclose(f) != 0 && !status[0]) status[0] = errno;
      if (!status[0] && std::rename(tmp.c_str(), path.c_str()) != 0) status[0] = errno;
      if (status[0]) std::remove(tmp.c_str()); // the previous fields.xdmf stays
    }
  }
  PetscCallMPI(MPI_Bcast(status, 2, MPI_INT, 0, comm));
  PetscCheck(!status[0], comm, PETSC_ERR_FILE_WRITE, "Cannot write %s/fields.xdmf: %s: free some space or choose a writable -output_dir",
             series.output_dir.c_str(), std::strerror(status[0]));
  PetscCheck(!status[1], comm, PETSC_ERR_FILE_WRITE,
             "%s/%s was deleted during the run (the output directory removed?): fields.xdmf now lists only the field files still "
             "there; the run stops. Keep the output directory until the run ends",
             series.output_dir.c_str(), status[1] ? FieldFileName(series.frames[status[1] - 1].step).c_str() : "");
  PetscFunctionReturn(0);
}

template void largest_bond_stretch<2>(const PointCloud &, const double *, const Families &, const BondState &, std::size_t, double *);
template void largest_bond_stretch<3>(const PointCloud &, const double *, const Families &, const BondState &, std::size_t, double *);
template PetscErrorCode WriteFieldFrame<2>(MPI_Comm, const NaturalOrder &, FieldSeries *, PetscInt, double, double, const PointFields &);
template PetscErrorCode WriteFieldFrame<3>(MPI_Comm, const NaturalOrder &, FieldSeries *, PetscInt, double, double, const PointFields &);
template PetscErrorCode WriteFieldIndex<2>(MPI_Comm, const FieldSeries &, PetscInt);
template PetscErrorCode WriteFieldIndex<3>(MPI_Comm, const FieldSeries &, PetscInt);

} // namespace bapd
