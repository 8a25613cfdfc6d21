// Checkpoints: writing, checking and reading back (checkpoint.hpp has the format).
#include "bapd/checkpoint.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <unistd.h>

#include "bapd/hdf5_io.hpp"
#include "bapd/scene.hpp"

namespace bapd {

namespace {

// splitmix64's finaliser: a cheap, well-mixed 64-bit hash step.
std::uint64_t Mix(std::uint64_t z)
{
  z += 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

std::uint64_t Bits(double x)
{
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// One entry of an order-independent checksum: the sum over entries (mod 2^64) does
// not depend on which rank holds which entry.
std::uint64_t Entry(std::uint64_t tag, std::uint64_t index, std::uint64_t bits) { return Mix(Mix(tag ^ Mix(index)) ^ bits); }

PetscErrorCode BcastString(MPI_Comm comm, std::string *s)
{
  PetscFunctionBegin;
  unsigned long long n = s->size();
  PetscCallMPI(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, comm));
  s->resize(n);
  if (n) PetscCallMPI(MPI_Bcast(s->data(), (int)n, MPI_CHAR, 0, comm));
  PetscFunctionReturn(0);
}

PetscErrorCode BcastDoubles(MPI_Comm comm, std::vector<double> *values)
{
  PetscFunctionBegin;
  unsigned long long n = values->size();
  PetscCallMPI(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, comm));
  values->resize(n);
  if (n) PetscCallMPI(MPI_Bcast(values->data(), (int)n, MPI_DOUBLE, 0, comm));
  PetscFunctionReturn(0);
}

// The checksum of the arrays of this rank's block, summed over the ranks.
PetscErrorCode ContentHash(MPI_Comm comm, const NaturalOrder &order, const double *u, const double *v,
                           const std::int32_t *family_size, const unsigned char *intact, const double *c33,
                           std::uint64_t *hash)
{
  PetscFunctionBegin;
  std::uint64_t h = 0;
  for (PetscInt k = 0; k < order.point_count; ++k) {
    const std::uint64_t p = (std::uint64_t)(order.point_start + k);
    for (int c = 0; c < 2; ++c) {
      h += Entry(1, 2 * p + c, Bits(u[2 * k + c]));
      h += Entry(2, 2 * p + c, Bits(v[2 * k + c]));
    }
    h += Entry(3, p, (std::uint64_t)family_size[k]);
  }
  for (PetscInt b = 0; b < order.bond_count; ++b) {
    const std::uint64_t g = (std::uint64_t)(order.bond_start + b);
    h += Entry(4, g, intact[b]);
    h += Entry(5, g, Bits(c33[b]));
  }
  PetscCallMPI(MPI_Allreduce(&h, hash, 1, MPI_UINT64_T, MPI_SUM, comm));
  PetscFunctionReturn(0);
}

// The checksum of the -relaxation adaptive arrays of this rank's block (relaxation.hpp).
PetscErrorCode RelaxationHash(MPI_Comm comm, const NaturalOrder &order, const double *u, const double *a, std::uint64_t *hash)
{
  PetscFunctionBegin;
  std::uint64_t h = 0;
  for (PetscInt k = 0; k < order.point_count; ++k)
    for (int c = 0; c < 2; ++c) {
      const std::uint64_t i = 2 * (std::uint64_t)(order.point_start + k) + c;
      h += Entry(9, i, Bits(u[2 * k + c])) + Entry(10, i, Bits(a[2 * k + c]));
    }
  PetscCallMPI(MPI_Allreduce(&h, hash, 1, MPI_UINT64_T, MPI_SUM, comm));
  PetscFunctionReturn(0);
}

// The checksum of the re-estimate's eigenvector in this rank's block (time_step_control.hpp).
PetscErrorCode EigenvectorHash(MPI_Comm comm, const NaturalOrder &order, const double *e, std::uint64_t *hash)
{
  PetscFunctionBegin;
  std::uint64_t h = 0;
  for (PetscInt k = 0; k < 2 * order.point_count; ++k) h += Entry(12, 2 * (std::uint64_t)order.point_start + (std::uint64_t)k, Bits(e[k]));
  PetscCallMPI(MPI_Allreduce(&h, hash, 1, MPI_UINT64_T, MPI_SUM, comm));
  PetscFunctionReturn(0);
}

// Two arrays of 2 per owned point -> this rank's natural block (or back).
PetscErrorCode PairToNatural(const NaturalOrder &order, PetscInt owned_points, const double *a_local, const double *b_local,
                             std::vector<double> *a_block, std::vector<double> *b_block)
{
  MPI_Datatype four;

  PetscFunctionBegin;
  std::vector<double> local(4 * owned_points), block(4 * order.point_count);
  for (PetscInt i = 0; i < owned_points; ++i)
    for (int c = 0; c < 2; ++c) local[4 * i + c] = a_local[2 * i + c], local[4 * i + 2 + c] = b_local[2 * i + c];
  PetscCallMPI(MPI_Type_contiguous(4, MPI_DOUBLE, &four));
  PetscCallMPI(MPI_Type_commit(&four));
  PetscCall(ToNaturalOrder(order.owned_points, four, local.data(), block.data()));
  PetscCallMPI(MPI_Type_free(&four));
  a_block->resize(2 * order.point_count);
  b_block->resize(2 * order.point_count);
  for (PetscInt k = 0; k < order.point_count; ++k)
    for (int c = 0; c < 2; ++c) (*a_block)[2 * k + c] = block[4 * k + c], (*b_block)[2 * k + c] = block[4 * k + 2 + c];
  PetscFunctionReturn(0);
}

PetscErrorCode PairFromNatural(const NaturalOrder &order, PetscInt owned_points, const std::vector<double> &a_block,
                               const std::vector<double> &b_block, double *a_local, double *b_local)
{
  MPI_Datatype four;

  PetscFunctionBegin;
  std::vector<double> local(4 * owned_points), block(4 * order.point_count);
  for (PetscInt k = 0; k < order.point_count; ++k)
    for (int c = 0; c < 2; ++c) block[4 * k + c] = a_block[2 * k + c], block[4 * k + 2 + c] = b_block[2 * k + c];
  PetscCallMPI(MPI_Type_contiguous(4, MPI_DOUBLE, &four));
  PetscCallMPI(MPI_Type_commit(&four));
  PetscCall(FromNaturalOrder(order.owned_points, four, block.data(), local.data()));
  PetscCallMPI(MPI_Type_free(&four));
  for (PetscInt i = 0; i < owned_points; ++i)
    for (int c = 0; c < 2; ++c) a_local[2 * i + c] = local[4 * i + c], b_local[2 * i + c] = local[4 * i + 2 + c];
  PetscFunctionReturn(0);
}

// The header values that steer the continuation, folded into the checksum too.
std::uint64_t HeaderHash(const CheckpointHeader &h)
{
  std::uint64_t sum = Entry(6, 0, (std::uint64_t)h.step) + Entry(6, 1, Bits(h.time)) + Entry(6, 2, Bits(h.time_step)) +
                      Entry(6, 3, Bits(h.end_time)) + Entry(6, 4, Bits(h.end_time_original)) + Entry(6, 5, (std::uint64_t)h.static_hold_done);
  for (std::size_t k = 0; k < h.schedule_current.size(); ++k) sum += Entry(7, k, Bits(h.schedule_current[k]));
  for (std::size_t k = 0; k < h.schedule_original.size(); ++k) sum += Entry(8, k, Bits(h.schedule_original[k]));
  if (h.relaxation_records > 0) sum += Entry(11, 0, (std::uint64_t)h.relaxation_records); // absent in version 1
  if (h.step_lambda > 0) // absent in versions 1 and 2
    sum += Entry(13, 0, Bits(h.step_lambda)) + Entry(13, 1, Bits(h.step_stiffness_dt)) + Entry(13, 2, Bits(h.step_shortest)) +
           Entry(13, 3, (std::uint64_t)h.step_next_estimate) + Entry(13, 4, (std::uint64_t)h.step_by_stiffness) +
           Entry(13, 5, (std::uint64_t)h.step_by_travel) + Entry(13, 6, Bits(h.step_stretch));
  if (h.step_interval_now > 0) // absent in versions 1 to 3
    sum += Entry(13, 7, (std::uint64_t)h.step_interval_now) + Entry(13, 8, Bits(h.step_stretch_increment));
  if (h.step_indicator > 0) sum += Entry(13, 9, Bits(h.step_indicator)); // absent in versions 1 to 4, and before any search
  return sum;
}

// Format version 3: the checksum of what rank 0 stores and a restart restores
// besides the arrays (the options, history.csv, static_states.csv, the field frames
// and the reason), checked as the header is read, before the options are merged.
std::uint64_t TextHash(const CheckpointHeader &h)
{
  std::uint64_t sum  = 0;
  auto          text = [&](std::uint64_t tag, const std::string &t) {
    sum += Entry(tag, ~0ULL, t.size());
    for (std::size_t k = 0; k < t.size(); k += 8) {
      std::uint64_t chunk = 0;
      std::memcpy(&chunk, t.data() + k, std::min<std::size_t>(8, t.size() - k));
      sum += Entry(tag, k, chunk);
    }
  };
  text(12, h.options);
  text(13, h.history);
  text(14, h.static_states);
  text(15, h.reason);
  sum += Entry(16, ~0ULL, h.field_frames.size());
  for (std::size_t k = 0; k < h.field_frames.size(); ++k) sum += Entry(16, k, Bits(h.field_frames[k]));
  return sum;
}

// "600s", "10min", "2h" -> seconds; "1000" -> steps. False if neither.
bool ParseInterval(const std::string &text, PetscInt *steps, double *seconds)
{
  *steps   = 0;
  *seconds = 0;
  if (text.empty()) return true;
  char        *end   = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || !(value >= 0) || !std::isfinite(value)) return false;
  std::string unit(end);
  unit.erase(std::remove_if(unit.begin(), unit.end(), [](unsigned char c) { return std::isspace(c); }), unit.end());
  if (unit.empty()) {
    if (value != std::floor(value) || value > 1e15) return false;
    *steps = (PetscInt)value;
    return true;
  }
  if (unit == "s") *seconds = value;
  else if (unit == "min") *seconds = 60 * value;
  else if (unit == "h") *seconds = 3600 * value;
  else return false;
  return true;
}

} // namespace

PetscErrorCode CheckpointOptionsFromOptions(MPI_Comm comm, CheckpointOptions *options)
{
  char      interval[128] = "", restart[PETSC_MAX_PATH_LEN] = "";
  PetscBool has_interval = PETSC_FALSE, has_restart = PETSC_FALSE;

  PetscFunctionBegin;
  for (const char *name : {"-checkpoint_interval", "-checkpoint_on_error", "-restart"}) RegisterOptionName(name);
  PetscOptionsBegin(comm, nullptr, "Checkpoints and restart", "bapd");
  PetscCall(PetscOptionsString("-checkpoint_interval",
                               "Between checkpoints (<output_dir>/checkpoint.h5, also written at the end): steps (1000) or wall-clock "
                               "time (600s, 10min, 2h); absent: only on a signal (SIGTERM, SIGINT, SIGUSR1) or an error",
                               "docs/options.md", "", interval, sizeof interval, &has_interval));
  PetscCall(PetscOptionsBool("-checkpoint_on_error", "On divergence, write the last good state as a checkpoint (keeps a copy of the state every step)",
                             "docs/options.md", options->on_error, &options->on_error, nullptr));
  PetscCall(PetscOptionsString("-restart", "Continue from this checkpoint file (its options are the defaults)", "docs/options.md", "", restart,
                               sizeof restart, &has_restart));
  PetscOptionsEnd();
  const bool ok = ParseInterval(interval, &options->step_interval, &options->wall_interval);
  PetscCheck(ok, comm, PETSC_ERR_USER,
             "-checkpoint_interval %s: give a number of steps (e.g. 1000) or a wall-clock time with a unit (600s, 10min or 2h)", interval);
  PetscCheck(!has_restart || restart[0], comm, PETSC_ERR_USER, "-restart needs the checkpoint file to continue from (e.g. -restart output/checkpoint.h5)");
  options->restart = has_restart ? restart : "";
  PetscFunctionReturn(0);
}

PetscErrorCode ComputeGeometryFingerprint(MPI_Comm comm, const Layout &layout, const Families &families, double dx,
                                          double horizon, GeometryFingerprint *fingerprint)
{
  PetscFunctionBegin;
  std::uint64_t hash = 0;
  long long     bonds = 0;
  for (PetscInt i = 0; i < layout.n_owned; ++i) {
    std::uint64_t h = Mix((std::uint64_t)layout.cloud.natural_id[i]);
    h               = Mix(h ^ Bits(layout.cloud.x[2 * i]));
    h               = Mix(h ^ Bits(layout.cloud.x[2 * i + 1]));
    for (std::size_t b = families.offsets[i]; b < families.offsets[i + 1]; ++b) h = Mix(h ^ (std::uint64_t)layout.cloud.natural_id[families.neighbour[b]]);
    hash += h;
    bonds += (long long)families.size((std::size_t)i);
  }
  PetscCallMPI(MPI_Allreduce(&hash, &fingerprint->hash, 1, MPI_UINT64_T, MPI_SUM, comm));
  long long total = 0;
  PetscCallMPI(MPI_Allreduce(&bonds, &total, 1, MPI_LONG_LONG, MPI_SUM, comm));
  fingerprint->points  = layout.n_global;
  fingerprint->bonds   = total;
  fingerprint->dx      = dx;
  fingerprint->horizon = horizon;
  PetscFunctionReturn(0);
}

bool SameGeometry(const GeometryFingerprint &a, const GeometryFingerprint &b)
{
  return a.points == b.points && a.bonds == b.bonds && a.dx == b.dx && a.horizon == b.horizon && a.hash == b.hash;
}

PetscErrorCode WriteCheckpoint(MPI_Comm comm, const std::string &path, const NaturalOrder &order, const Families &families,
                               CheckpointHeader *header, const CheckpointState &state)
{
  PetscMPIInt  rank, size;
  MPI_Datatype four;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  // Owned data -> this rank's natural block.
  PetscInt owned_points;
  PetscCall(PetscSFGetGraph(order.owned_points, nullptr, &owned_points, nullptr, nullptr));
  std::vector<double> uv_local(4 * owned_points), uv_block(4 * order.point_count);
  for (PetscInt i = 0; i < owned_points; ++i)
    for (int c = 0; c < 2; ++c) {
      uv_local[4 * i + c]     = state.u[2 * i + c];
      uv_local[4 * i + 2 + c] = state.v[2 * i + c];
    }
  PetscCallMPI(MPI_Type_contiguous(4, MPI_DOUBLE, &four));
  PetscCallMPI(MPI_Type_commit(&four));
  PetscCall(ToNaturalOrder(order.owned_points, four, uv_local.data(), uv_block.data()));
  PetscCallMPI(MPI_Type_free(&four));
  std::vector<double> u(2 * order.point_count), v(2 * order.point_count);
  for (PetscInt k = 0; k < order.point_count; ++k)
    for (int c = 0; c < 2; ++c) {
      u[2 * k + c] = uv_block[4 * k + c];
      v[2 * k + c] = uv_block[4 * k + 2 + c];
    }
  const std::size_t          owned_bonds = families.offsets[owned_points];
  std::vector<unsigned char> intact_local(owned_bonds), intact(order.bond_count);
  for (PetscInt i = 0; i < owned_points; ++i)
    for (std::size_t b = families.offsets[i]; b < families.offsets[i + 1]; ++b)
      intact_local[b] = state.bonds->is_intact((std::size_t)i, b - families.offsets[i]) ? 1 : 0;
  std::vector<double> c33(order.bond_count);
  PetscCall(ToNaturalOrder(order.owned_bonds, MPI_UNSIGNED_CHAR, intact_local.data(), intact.data()));
  PetscCall(ToNaturalOrder(order.owned_bonds, MPI_DOUBLE, state.c33, c33.data()));
  std::vector<std::int32_t> family_size(order.family_size.begin(), order.family_size.end());
  PetscCall(ContentHash(comm, order, u.data(), v.data(), family_size.data(), intact.data(), c33.data(), &header->content_hash));
  std::vector<double> relax_u, relax_a;
  if (header->relaxation_records > 0) {
    std::uint64_t relax_hash = 0;
    PetscCall(PairToNatural(order, owned_points, state.relaxation_u, state.relaxation_a, &relax_u, &relax_a));
    PetscCall(RelaxationHash(comm, order, relax_u.data(), relax_a.data(), &relax_hash));
    header->content_hash += relax_hash;
  }
  std::vector<double> eigenvector, unused;
  if (header->step_lambda > 0) {
    std::uint64_t step_hash = 0;
    PetscCall(PairToNatural(order, owned_points, state.step_eigenvector, state.step_eigenvector, &eigenvector, &unused));
    PetscCall(EigenvectorHash(comm, order, eigenvector.data(), &step_hash));
    header->content_hash += step_hash;
  }
  header->content_hash += HeaderHash(*header);
  header->ranks = size;
  std::uint64_t text_hash = rank == 0 ? TextHash(*header) : 0; // rank 0's texts are the ones written
  PetscCallMPI(MPI_Bcast(&text_hash, 1, MPI_UINT64_T, 0, comm));

  const std::string tmp = path + ".tmp";
  {
    // Its size: the arrays (with the re-estimate's eigenvector), the texts and tables
    // (rank 0's, which writes them), and about 30 datasets, groups and attributes.
    const std::uint64_t points = (std::uint64_t)order.n_points, bonds = (std::uint64_t)order.n_bonds;
    std::uint64_t       data = points * (2 * 16 + 4) + bonds * (1 + 8) + (header->relaxation_records > 0 ? 2 * 16 * points : 0) +
                         (state.step_eigenvector ? 16 * points : 0);
    std::uint64_t       text = header->options.size() + header->history.size() + header->static_states.size() +
                         8 * (header->field_frames.size() + header->schedule_original.size() + header->schedule_current.size());
    PetscCallMPI(MPI_Bcast(&text, 1, MPI_UINT64_T, 0, comm));
    H5ParallelFile f;
    PetscCall(f.Create(comm, tmp, H5FileBytes(data + text, 32)));
    PetscCall(f.WriteAttribute("/", "format", std::string("bapd checkpoint")));
    PetscCall(f.WriteAttribute("/", "format_version", header->format_version));
    PetscCall(f.WriteAttribute("/", "step", (std::int64_t)header->step));
    PetscCall(f.WriteAttribute("/", "time_s", header->time));
    PetscCall(f.WriteAttribute("/", "time_step_s", header->time_step));
    PetscCall(f.WriteAttribute("/", "stretch", header->stretch));
    PetscCall(f.WriteAttribute("/", "reason", header->reason));
    PetscCall(f.WriteAttribute("/", "ranks", header->ranks));
    PetscCall(f.WriteAttribute("/", "content_hash", header->content_hash));
    PetscCall(f.WriteAttribute("/", "text_hash", text_hash));
    PetscCall(f.WriteAttribute("/", "end_time_original_s", header->end_time_original));
    PetscCall(f.WriteAttribute("/", "end_time_s", header->end_time));
    PetscCall(f.WriteAttribute("/", "static_hold_done", header->static_hold_done));
    PetscCall(f.CreateGroup("/geometry"));
    PetscCall(f.WriteAttribute("/geometry", "points", header->geometry.points));
    PetscCall(f.WriteAttribute("/geometry", "bonds", header->geometry.bonds));
    PetscCall(f.WriteAttribute("/geometry", "dx_m", header->geometry.dx));
    PetscCall(f.WriteAttribute("/geometry", "horizon_m", header->geometry.horizon));
    PetscCall(f.WriteAttribute("/geometry", "hash", header->geometry.hash));
    const hsize_t P = (hsize_t)order.n_points, B = (hsize_t)order.n_bonds;
    PetscCall(f.CreateGroup("/points"));
    PetscCall(f.WriteBlock("/points/displacement", H5T_NATIVE_DOUBLE, P, 2, order.point_start, order.point_count, u.data()));
    PetscCall(f.WriteBlock("/points/velocity", H5T_NATIVE_DOUBLE, P, 2, order.point_start, order.point_count, v.data()));
    PetscCall(f.WriteBlock("/points/family_size", H5T_NATIVE_INT32, P, 0, order.point_start, order.point_count, family_size.data()));
    PetscCall(f.CreateGroup("/bonds"));
    PetscCall(f.WriteBlock("/bonds/intact", H5T_NATIVE_UCHAR, B, 0, order.bond_start, order.bond_count, intact.data()));
    PetscCall(f.WriteBlock("/bonds/c33", H5T_NATIVE_DOUBLE, B, 0, order.bond_start, order.bond_count, c33.data()));
    PetscCall(f.CreateGroup("/run"));
    PetscCall(f.WriteText("/run/options", header->options));
    PetscCall(f.WriteText("/run/history", header->history));
    PetscCall(f.WriteText("/run/static_states", header->static_states));
    PetscCall(f.WriteRoot("/run/schedule_original", H5T_NATIVE_DOUBLE, header->schedule_original.size(), header->schedule_original.data()));
    PetscCall(f.WriteRoot("/run/schedule_current", H5T_NATIVE_DOUBLE, header->schedule_current.size(), header->schedule_current.data()));
    if (header->relaxation_records > 0) {
      PetscCall(f.CreateGroup("/relaxation"));
      PetscCall(f.WriteAttribute("/relaxation", "records", header->relaxation_records));
      PetscCall(f.WriteBlock("/relaxation/displacement", H5T_NATIVE_DOUBLE, P, 2, order.point_start, order.point_count, relax_u.data()));
      PetscCall(f.WriteBlock("/relaxation/acceleration", H5T_NATIVE_DOUBLE, P, 2, order.point_start, order.point_count, relax_a.data()));
    }
    if (header->step_lambda > 0) {
      PetscCall(f.CreateGroup("/time_step"));
      PetscCall(f.WriteAttribute("/time_step", "lambda_per_s2", header->step_lambda));
      PetscCall(f.WriteAttribute("/time_step", "stiffness_dt_s", header->step_stiffness_dt));
      PetscCall(f.WriteAttribute("/time_step", "shortest_dt_s", header->step_shortest));
      PetscCall(f.WriteAttribute("/time_step", "next_estimate", header->step_next_estimate));
      PetscCall(f.WriteAttribute("/time_step", "by_stiffness", header->step_by_stiffness));
      PetscCall(f.WriteAttribute("/time_step", "by_travel", header->step_by_travel));
      PetscCall(f.WriteAttribute("/time_step", "stretch", header->step_stretch));
      PetscCall(f.WriteAttribute("/time_step", "interval_now", header->step_interval_now));
      PetscCall(f.WriteAttribute("/time_step", "stretch_increment", header->step_stretch_increment));
      PetscCall(f.WriteAttribute("/time_step", "indicator", header->step_indicator));
      PetscCall(f.WriteBlock("/time_step/eigenvector", H5T_NATIVE_DOUBLE, P, 2, order.point_start, order.point_count, eigenvector.data()));
    }
    const hsize_t frames = header->field_frames.size() / 2;
    PetscCall(f.WriteBlock("/run/field_frames", H5T_NATIVE_DOUBLE, frames, 2, 0, rank == 0 ? frames : 0, header->field_frames.data()));
    PetscCall(f.Close());
  }
  // Only a complete file takes the name: flushed to the disk, then renamed over the
  // previous checkpoint in one step.
  int error = 0;
  if (rank == 0) {
    const int fd = ::open(tmp.c_str(), O_RDONLY);
    if (fd < 0 || ::fsync(fd) != 0) error = errno;
    if (fd >= 0 && ::close(fd) != 0 && !error) error = errno;
    if (!error && std::rename(tmp.c_str(), path.c_str()) != 0) error = errno;
    if (error) std::remove(tmp.c_str()); // the previous checkpoint stays as it was
  }
  PetscCallMPI(MPI_Bcast(&error, 1, MPI_INT, 0, comm));
  PetscCheck(!error, comm, PETSC_ERR_FILE_WRITE, "Cannot write %s: %s while saving %s; the previous checkpoint (if any) is kept: free some space or choose another -output_dir",
             path.c_str(), std::strerror(error), tmp.c_str());
  PetscFunctionReturn(0);
}

namespace {

// Rank 0: everything about the file that can be checked without the scene.
std::string ReadHeaderSerial(const std::string &path, CheckpointHeader *h)
{
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    return "Cannot open checkpoint '" + path + "': no such file (check the path given to -restart)";
  H5Quiet     quiet;
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0)
    return "Checkpoint '" + path + "' cannot be read: it is not an HDF5 file, or it is truncated (a copy cut short?)";
  std::string problem, format;
  auto        damaged = [&](const std::string &what) {
    if (problem.empty()) problem = "Checkpoint '" + path + "' is damaged: " + what + " (use an earlier checkpoint)";
  };
  if (!H5ReadAttribute(file, "/", "format", &format) || format != "bapd checkpoint")
    problem = "'" + path + "' is not a bapd checkpoint (it has no format attribute \"bapd checkpoint\")";
  else if (!H5ReadAttribute(file, "/", "format_version", &h->format_version))
    damaged("attribute format_version is missing");
  else if (h->format_version < kCheckpointOldestFormatVersion || h->format_version > kCheckpointFormatVersion) {
    char msg[512];
    std::snprintf(msg, sizeof msg, "Checkpoint '%s' has format version %lld; this bapd reads versions %lld to %lld: continue it with the bapd that wrote it",
                  path.c_str(), (long long)h->format_version, (long long)kCheckpointOldestFormatVersion, (long long)kCheckpointFormatVersion);
    problem = msg;
  }
  if (problem.empty()) {
    std::int64_t step = 0;
    if (!H5ReadAttribute(file, "/", "step", &step)) damaged("attribute step is missing");
    h->step = (PetscInt)step;
    if (!H5ReadAttribute(file, "/", "time_s", &h->time)) damaged("attribute time_s is missing");
    if (!H5ReadAttribute(file, "/", "time_step_s", &h->time_step)) damaged("attribute time_step_s is missing");
    if (!H5ReadAttribute(file, "/", "stretch", &h->stretch)) damaged("attribute stretch is missing");
    if (!H5ReadAttribute(file, "/", "reason", &h->reason)) damaged("attribute reason is missing");
    if (!H5ReadAttribute(file, "/", "ranks", &h->ranks)) damaged("attribute ranks is missing");
    if (!H5ReadAttribute(file, "/", "content_hash", &h->content_hash)) damaged("attribute content_hash is missing");
    if (!H5ReadAttribute(file, "/", "end_time_original_s", &h->end_time_original)) damaged("attribute end_time_original_s is missing");
    if (!H5ReadAttribute(file, "/", "end_time_s", &h->end_time)) damaged("attribute end_time_s is missing");
    if (!H5ReadAttribute(file, "/", "static_hold_done", &h->static_hold_done)) damaged("attribute static_hold_done is missing");
    if (!H5ReadAttribute(file, "/geometry", "points", &h->geometry.points)) damaged("attribute /geometry/points is missing");
    if (!H5ReadAttribute(file, "/geometry", "bonds", &h->geometry.bonds)) damaged("attribute /geometry/bonds is missing");
    if (!H5ReadAttribute(file, "/geometry", "dx_m", &h->geometry.dx)) damaged("attribute /geometry/dx_m is missing");
    if (!H5ReadAttribute(file, "/geometry", "horizon_m", &h->geometry.horizon)) damaged("attribute /geometry/horizon_m is missing");
    if (!H5ReadAttribute(file, "/geometry", "hash", &h->geometry.hash)) damaged("attribute /geometry/hash is missing");
  }
  if (problem.empty()) {
    const hsize_t P = (hsize_t)h->geometry.points, B = (hsize_t)h->geometry.bonds;
    const struct {
      const char          *name;
      std::vector<hsize_t> shape;
    } expected[] = {{"/points/displacement", {P, 2}}, {"/points/velocity", {P, 2}}, {"/points/family_size", {P}},
                    {"/bonds/intact", {B}},         {"/bonds/c33", {B}}};
    for (const auto &e : expected)
      if (H5DatasetShape(file, e.name) != e.shape) damaged(std::string("dataset ") + e.name + " is missing or has the wrong shape");
    const std::vector<hsize_t> frames = H5DatasetShape(file, "/run/field_frames");
    if (frames.size() != 2 || frames[1] != 2) damaged("dataset /run/field_frames is missing or has the wrong shape");
    if (problem.empty() && !H5ReadText(file, "/run/options", &h->options)) damaged("dataset /run/options cannot be read");
    if (problem.empty() && !H5ReadText(file, "/run/history", &h->history)) damaged("dataset /run/history cannot be read");
    if (problem.empty() && !H5ReadText(file, "/run/static_states", &h->static_states)) damaged("dataset /run/static_states cannot be read");
    if (problem.empty() && !H5ReadDoubles(file, "/run/schedule_original", &h->schedule_original)) damaged("dataset /run/schedule_original cannot be read");
    if (problem.empty() && !H5ReadDoubles(file, "/run/schedule_current", &h->schedule_current)) damaged("dataset /run/schedule_current cannot be read");
    if (problem.empty() && h->schedule_original.size() != h->schedule_current.size()) damaged("the schedule datasets differ in length");
    if (problem.empty() && frames.size() == 2 && frames[0] > 0 && !H5ReadDoubles(file, "/run/field_frames", &h->field_frames))
      damaged("dataset /run/field_frames cannot be read");
    std::uint64_t text_hash = 0; // version 3 on; older files have none
    if (problem.empty() && h->format_version >= 3 && !H5ReadAttribute(file, "/", "text_hash", &text_hash))
      damaged("attribute text_hash is missing");
    if (problem.empty() && h->format_version >= 3 && text_hash != TextHash(*h))
      problem = "Checkpoint '" + path + "' is corrupt: its stored options, history, static states or field list (/run) do not match "
                "the checksum written with them (use an earlier checkpoint)";
    // -relaxation adaptive (version 2): optional.
    if (problem.empty() && H5Lexists(file, "/relaxation", H5P_DEFAULT) > 0) {
      if (!H5ReadAttribute(file, "/relaxation", "records", &h->relaxation_records) || h->relaxation_records < 1)
        damaged("attribute /relaxation/records is missing");
      for (const char *name : {"/relaxation/displacement", "/relaxation/acceleration"})
        if (H5DatasetShape(file, name) != std::vector<hsize_t>{P, 2}) damaged(std::string("dataset ") + name + " is missing or has the wrong shape");
    }
    // The re-estimated step (version 3): optional.
    if (problem.empty() && H5Lexists(file, "/time_step", H5P_DEFAULT) > 0) {
      if (!H5ReadAttribute(file, "/time_step", "lambda_per_s2", &h->step_lambda) || !(h->step_lambda > 0) ||
          !H5ReadAttribute(file, "/time_step", "stiffness_dt_s", &h->step_stiffness_dt) ||
          !H5ReadAttribute(file, "/time_step", "shortest_dt_s", &h->step_shortest) ||
          !H5ReadAttribute(file, "/time_step", "next_estimate", &h->step_next_estimate) ||
          !H5ReadAttribute(file, "/time_step", "by_stiffness", &h->step_by_stiffness) ||
          !H5ReadAttribute(file, "/time_step", "by_travel", &h->step_by_travel) ||
          !H5ReadAttribute(file, "/time_step", "stretch", &h->step_stretch))
        damaged("an attribute of /time_step is missing");
      if (h->format_version >= 4 && (!H5ReadAttribute(file, "/time_step", "interval_now", &h->step_interval_now) || h->step_interval_now < 1 ||
                                     !H5ReadAttribute(file, "/time_step", "stretch_increment", &h->step_stretch_increment)))
        damaged("attribute /time_step/interval_now or stretch_increment is missing");
      if (h->format_version >= 5 && !H5ReadAttribute(file, "/time_step", "indicator", &h->step_indicator))
        damaged("attribute /time_step/indicator is missing");
      if (H5DatasetShape(file, "/time_step/eigenvector") != std::vector<hsize_t>{P, 2})
        damaged("dataset /time_step/eigenvector is missing or has the wrong shape");
    }
  }
  H5Fclose(file);
  return problem;
}

} // namespace

PetscErrorCode ReadCheckpointHeader(MPI_Comm comm, const std::string &path, CheckpointHeader *header)
{
  PetscMPIInt rank;
  std::string problem;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  *header = CheckpointHeader();
  if (rank == 0) problem = ReadHeaderSerial(path, header);
  PetscCall(BcastString(comm, &problem));
  PetscCheck(problem.empty(), comm, PETSC_ERR_FILE_UNEXPECTED, "%s", problem.c_str());
  long long     ints[11]  = {(long long)header->step,            (long long)header->ranks,
                             (long long)header->geometry.points, (long long)header->geometry.bonds,
                             (long long)header->format_version,  (long long)header->static_hold_done,
                             (long long)header->relaxation_records, (long long)header->step_next_estimate,
                             (long long)header->step_by_stiffness,  (long long)header->step_by_travel,
                             (long long)header->step_interval_now};
  double        reals[13] = {header->time,        header->time_step,         header->stretch, header->geometry.dx,
                             header->geometry.horizon, header->end_time_original, header->end_time,
                             header->step_lambda, header->step_stiffness_dt, header->step_shortest, header->step_stretch,
                             header->step_stretch_increment, header->step_indicator};
  std::uint64_t hashes[2] = {header->content_hash, header->geometry.hash};
  PetscCallMPI(MPI_Bcast(ints, 11, MPI_LONG_LONG, 0, comm));
  PetscCallMPI(MPI_Bcast(reals, 13, MPI_DOUBLE, 0, comm));
  PetscCallMPI(MPI_Bcast(hashes, 2, MPI_UINT64_T, 0, comm));
  header->step             = (PetscInt)ints[0];
  header->ranks            = ints[1];
  header->geometry.points  = ints[2];
  header->geometry.bonds   = ints[3];
  header->format_version   = ints[4];
  header->static_hold_done = ints[5];
  header->relaxation_records = ints[6];
  header->step_next_estimate = ints[7];
  header->step_by_stiffness  = ints[8];
  header->step_by_travel     = ints[9];
  header->step_interval_now  = ints[10];
  header->step_lambda        = reals[7];
  header->step_stiffness_dt  = reals[8];
  header->step_shortest      = reals[9];
  header->step_stretch       = reals[10];
  header->step_stretch_increment = reals[11];
  header->step_indicator         = reals[12];
  header->end_time_original = reals[5];
  header->end_time          = reals[6];
  header->time             = reals[0];
  header->time_step        = reals[1];
  header->stretch          = reals[2];
  header->geometry.dx      = reals[3];
  header->geometry.horizon = reals[4];
  header->content_hash     = hashes[0];
  header->geometry.hash    = hashes[1];
  PetscCall(BcastString(comm, &header->reason));
  PetscCall(BcastString(comm, &header->options));
  PetscCall(BcastString(comm, &header->history));
  PetscCall(BcastString(comm, &header->static_states));
  PetscCall(BcastDoubles(comm, &header->field_frames));
  PetscCall(BcastDoubles(comm, &header->schedule_original));
  PetscCall(BcastDoubles(comm, &header->schedule_current));
  PetscFunctionReturn(0);
}

PetscErrorCode ReadCheckpointState(MPI_Comm comm, const std::string &path, const NaturalOrder &order,
                                   const Families &families, const CheckpointHeader &header,
                                   const GeometryFingerprint &geometry, const CheckpointState &state)
{
  MPI_Datatype four;

  PetscFunctionBegin;
  const GeometryFingerprint &g = header.geometry;
  PetscCheck(SameGeometry(g, geometry), comm, PETSC_ERR_USER,
             "Checkpoint '%s' belongs to another body: it holds %lld points and %lld bonds (dx %g m, horizon %g m), this scene "
             "%lld points and %lld bonds (dx %g m, horizon %g m)%s. Restart with the scene that wrote it: its options are "
             "stored in the checkpoint and apply unless the command line overrides them",
             path.c_str(), (long long)g.points, (long long)g.bonds, g.dx, g.horizon, (long long)geometry.points,
             (long long)geometry.bonds, geometry.dx, geometry.horizon,
             g.points == geometry.points && g.bonds == geometry.bonds && g.dx == geometry.dx && g.horizon == geometry.horizon
               ? " and the same counts but other positions, holes or notches"
               : "");
  std::vector<double>        u(2 * order.point_count), v(2 * order.point_count), c33(order.bond_count);
  std::vector<double>        relax_u, relax_a; // -relaxation adaptive, when the file has it
  std::vector<double>        eigenvector;      // the re-estimated step, when the file has it
  std::vector<std::int32_t>  family_size(order.point_count);
  std::vector<unsigned char> intact(order.bond_count);
  {
    H5ParallelFile f;
    const hsize_t  P = (hsize_t)order.n_points, B = (hsize_t)order.n_bonds;
    PetscCall(f.Open(comm, path));
    PetscCall(f.ReadBlock("/points/displacement", H5T_NATIVE_DOUBLE, P, 2, order.point_start, order.point_count, u.data()));
    PetscCall(f.ReadBlock("/points/velocity", H5T_NATIVE_DOUBLE, P, 2, order.point_start, order.point_count, v.data()));
    PetscCall(f.ReadBlock("/points/family_size", H5T_NATIVE_INT32, P, 0, order.point_start, order.point_count, family_size.data()));
    PetscCall(f.ReadBlock("/bonds/intact", H5T_NATIVE_UCHAR, B, 0, order.bond_start, order.bond_count, intact.data()));
    PetscCall(f.ReadBlock("/bonds/c33", H5T_NATIVE_DOUBLE, B, 0, order.bond_start, order.bond_count, c33.data()));
    if (header.relaxation_records > 0) {
      relax_u.resize(2 * order.point_count);
      relax_a.resize(2 * order.point_count);
      PetscCall(f.ReadBlock("/relaxation/displacement", H5T_NATIVE_DOUBLE, P, 2, order.point_start, order.point_count, relax_u.data()));
      PetscCall(f.ReadBlock("/relaxation/acceleration", H5T_NATIVE_DOUBLE, P, 2, order.point_start, order.point_count, relax_a.data()));
    }
    if (header.step_lambda > 0) {
      eigenvector.resize(2 * order.point_count);
      PetscCall(f.ReadBlock("/time_step/eigenvector", H5T_NATIVE_DOUBLE, P, 2, order.point_start, order.point_count, eigenvector.data()));
    }
    PetscCall(f.Close());
  }
  std::uint64_t hash = 0;
  PetscCall(ContentHash(comm, order, u.data(), v.data(), family_size.data(), intact.data(), c33.data(), &hash));
  if (header.relaxation_records > 0) {
    std::uint64_t relax_hash = 0;
    PetscCall(RelaxationHash(comm, order, relax_u.data(), relax_a.data(), &relax_hash));
    hash += relax_hash;
  }
  if (header.step_lambda > 0) {
    std::uint64_t step_hash = 0;
    PetscCall(EigenvectorHash(comm, order, eigenvector.data(), &step_hash));
    hash += step_hash;
  }
  hash += HeaderHash(header);
  PetscCheck(hash == header.content_hash, comm, PETSC_ERR_FILE_UNEXPECTED,
             "Checkpoint '%s' is corrupt: its data do not match the checksum written with them (use an earlier checkpoint)", path.c_str());

  // Block -> layout: u, v of owned points; bond bits and C33 of every family point
  // (ring-1 ghosts take their owner's values, as after every breaking pass).
  PetscInt owned_points;
  PetscCall(PetscSFGetGraph(order.owned_points, nullptr, &owned_points, nullptr, nullptr));
  std::vector<double> uv_block(4 * order.point_count), uv_local(4 * owned_points);
  for (PetscInt k = 0; k < order.point_count; ++k)
    for (int c = 0; c < 2; ++c) {
      uv_block[4 * k + c]     = u[2 * k + c];
      uv_block[4 * k + 2 + c] = v[2 * k + c];
    }
  PetscCallMPI(MPI_Type_contiguous(4, MPI_DOUBLE, &four));
  PetscCallMPI(MPI_Type_commit(&four));
  PetscCall(FromNaturalOrder(order.owned_points, four, uv_block.data(), uv_local.data()));
  PetscCallMPI(MPI_Type_free(&four));
  for (PetscInt i = 0; i < owned_points; ++i)
    for (int c = 0; c < 2; ++c) {
      state.u[2 * i + c] = uv_local[4 * i + c];
      state.v[2 * i + c] = uv_local[4 * i + 2 + c];
    }
  if (header.relaxation_records > 0 && state.relaxation_u)
    PetscCall(PairFromNatural(order, owned_points, relax_u, relax_a, state.relaxation_u, state.relaxation_a));
  if (header.step_lambda > 0 && state.step_eigenvector) {
    std::vector<double> scratch(2 * owned_points);
    PetscCall(PairFromNatural(order, owned_points, eigenvector, eigenvector, state.step_eigenvector, scratch.data()));
  }
  const std::size_t          family_bonds = families.offsets[families.n_family];
  std::vector<unsigned char> intact_local(family_bonds);
  PetscCall(FromNaturalOrder(order.family_bonds, MPI_UNSIGNED_CHAR, intact.data(), intact_local.data()));
  PetscCall(FromNaturalOrder(order.family_bonds, MPI_DOUBLE, c33.data(), state.c33));
  BondState        &bs = *state.bonds;
  const std::size_t W  = bs.mask_words;
  for (std::size_t i = 0; i < families.n_family; ++i) {
    std::uint64_t *mask = bs.intact.data() + i * W;
    std::fill(mask, mask + W, 0);
    for (std::size_t b = families.offsets[i]; b < families.offsets[i + 1]; ++b) {
      const std::size_t q = b - families.offsets[i];
      if (intact_local[b]) mask[q / 64] |= std::uint64_t(1) << (q % 64);
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode CheckpointMergeOptions(MPI_Comm comm)
{
  char      path[PETSC_MAX_PATH_LEN] = "";
  PetscBool has                      = PETSC_FALSE;

  PetscFunctionBegin;
  RegisterOptionName("-restart");
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-restart", path, sizeof path, &has));
  if (!has) PetscFunctionReturn(0);
  PetscCheck(path[0], comm, PETSC_ERR_USER, "-restart needs the checkpoint file to continue from (e.g. -restart output/checkpoint.h5)");
  CheckpointHeader header;
  PetscCall(ReadCheckpointHeader(comm, path, &header));
  // The stored database, parsed by PETSc itself; each of its options that the
  // command line does not set is added.
  PetscOptions stored;
  PetscInt     n      = 0;
  char       **names  = nullptr;
  char       **values = nullptr;
  PetscCall(PetscOptionsCreate(&stored));
  PetscCall(PetscOptionsInsertString(stored, header.options.c_str()));
  PetscCall(PetscOptionsLeftGet(stored, &n, &names, &values));
  for (PetscInt k = 0; k < n; ++k) {
    const std::string name = std::string("-") + names[k];
    if (name == "-restart") continue;
    PetscBool given = PETSC_FALSE;
    PetscCall(PetscOptionsHasName(nullptr, nullptr, name.c_str(), &given));
    if (!given) PetscCall(PetscOptionsSetValue(nullptr, name.c_str(), values[k]));
  }
  PetscCall(PetscOptionsLeftRestore(stored, &n, &names, &values));
  PetscCall(PetscOptionsDestroy(&stored));
  PetscFunctionReturn(0);
}

} // namespace bapd
