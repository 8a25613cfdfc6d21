// Checkpoints: writing one (checkpoint.hpp has the format).
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <utility>
#include <variant>

#include "bapd/solver/io/checkpoint.hpp"
#include "bapd/solver/io/checkpoint_checksum.hpp"
#include "bapd/solver/io/hdf5_io.hpp"

namespace bapd {

namespace {

// One attribute: its name and value (the value's type is the attribute's).
using Attribute = std::pair<const char *, std::variant<double, std::int64_t, std::uint64_t, std::string>>;

// The attributes of object, in the order listed.
PetscErrorCode WriteAttributes(H5ParallelFile &f, const char *object, std::initializer_list<Attribute> attributes)
{
  PetscFunctionBegin;
  for (const Attribute &a : attributes)
    PetscCall(std::visit([&](const auto &value) { return f.WriteAttribute(object, a.first, value); }, a.second));
  PetscFunctionReturn(0);
}

// The checkpoint's file at `path` (the temporary name): the header's attributes, texts
// and tables (rank 0's) and this rank's natural block of the arrays.
template <int D>
PetscErrorCode WriteCheckpointFile(MPI_Comm comm, PetscMPIInt rank, const std::string &path, const NaturalOrder &order,
                                   const CheckpointHeader &header, const CheckpointBlock &block, std::uint64_t text_hash,
                                   bool has_eigenvector)
{
  PetscFunctionBegin;
  // Its size: the arrays (with the re-estimate's eigenvector), the texts and tables
  // (rank 0's, which writes them), and about 30 datasets, groups and attributes.
  const std::uint64_t points = (std::uint64_t)order.n_points, bonds = (std::uint64_t)order.n_bonds, vector = 8 * D;
  std::uint64_t       data = points * (2 * vector + 4) + bonds * (1 + (header.has_c33 ? 8 : 0) + (header.has_damage ? 8 : 0)) +
                       (header.relaxation_records > 0 ? 2 * vector * points : 0) + (has_eigenvector ? vector * points : 0);
  std::uint64_t       text = header.options.size() + header.history.size() + header.static_states.size() +
                       8 * (header.field_frames.size() + header.schedule_original.size() + header.schedule_current.size() +
                            header.energy_totals.size());
  PetscCallMPI(MPI_Bcast(&text, 1, MPI_UINT64_T, 0, comm));
  H5ParallelFile f;
  PetscCall(f.Create(comm, path, data + text, 32));
  PetscCall(WriteAttributes(f, "/", {{"format", std::string("bapd checkpoint")}, {"format_version", header.format_version},
                                     {"dimension", header.dimension}, {"step", (std::int64_t)header.step},
                                     {"time_s", header.time}, {"time_step_s", header.time_step}, {"stretch", header.stretch},
                                     {"reason", header.reason}, {"ranks", header.ranks}, {"content_hash", header.content_hash},
                                     {"text_hash", text_hash}, {"end_time_original_s", header.end_time_original},
                                     {"end_time_s", header.end_time}, {"static_hold_done", header.static_hold_done}}));
  PetscCall(f.CreateGroup("/geometry"));
  PetscCall(WriteAttributes(f, "/geometry", {{"points", header.geometry.points}, {"bonds", header.geometry.bonds},
                                             {"dx_m", header.geometry.dx}, {"horizon_m", header.geometry.horizon},
                                             {"hash", header.geometry.hash}}));
  const hsize_t P = (hsize_t)order.n_points, B = (hsize_t)order.n_bonds;
  PetscCall(f.CreateGroup("/points"));
  PetscCall(f.WriteBlock("/points/displacement", H5T_NATIVE_DOUBLE, P, D, order.point_start, order.point_count, block.u.data()));
  PetscCall(f.WriteBlock("/points/velocity", H5T_NATIVE_DOUBLE, P, D, order.point_start, order.point_count, block.v.data()));
  PetscCall(f.WriteBlock("/points/family_size", H5T_NATIVE_INT32, P, 0, order.point_start, order.point_count, block.family_size.data()));
  PetscCall(f.CreateGroup("/bonds"));
  PetscCall(f.WriteBlock("/bonds/intact", H5T_NATIVE_UCHAR, B, 0, order.bond_start, order.bond_count, block.intact.data()));
  if (header.has_c33) PetscCall(f.WriteBlock("/bonds/c33", H5T_NATIVE_DOUBLE, B, 0, order.bond_start, order.bond_count, block.c33.data()));
  if (header.has_damage)
    PetscCall(f.WriteBlock("/bonds/damage", H5T_NATIVE_DOUBLE, B, 0, order.bond_start, order.bond_count, block.damage.data()));
  PetscCall(f.CreateGroup("/run"));
  PetscCall(f.WriteText("/run/options", header.options));
  PetscCall(f.WriteText("/run/history", header.history));
  PetscCall(f.WriteText("/run/static_states", header.static_states));
  PetscCall(f.WriteRoot("/run/schedule_original", H5T_NATIVE_DOUBLE, header.schedule_original.size(), header.schedule_original.data()));
  PetscCall(f.WriteRoot("/run/schedule_current", H5T_NATIVE_DOUBLE, header.schedule_current.size(), header.schedule_current.data()));
  PetscCall(f.WriteRoot("/run/energy", H5T_NATIVE_DOUBLE, header.energy_totals.size(), header.energy_totals.data()));
  if (header.relaxation_records > 0) {
    PetscCall(f.CreateGroup("/relaxation"));
    PetscCall(f.WriteAttribute("/relaxation", "records", header.relaxation_records));
    PetscCall(f.WriteBlock("/relaxation/displacement", H5T_NATIVE_DOUBLE, P, D, order.point_start, order.point_count, block.relaxation_u.data()));
    PetscCall(f.WriteBlock("/relaxation/acceleration", H5T_NATIVE_DOUBLE, P, D, order.point_start, order.point_count, block.relaxation_a.data()));
  }
  if (header.step_lambda > 0) {
    PetscCall(f.CreateGroup("/time_step"));
    PetscCall(WriteAttributes(f, "/time_step", {{"lambda_per_s2", header.step_lambda},
                                                {"stiffness_dt_s", header.step_stiffness_dt},
                                                {"shortest_dt_s", header.step_shortest},
                                                {"next_estimate", header.step_next_estimate},
                                                {"by_stiffness", header.step_by_stiffness}, {"by_travel", header.step_by_travel},
                                                {"stretch", header.step_stretch}, {"interval_now", header.step_interval_now},
                                                {"stretch_increment", header.step_stretch_increment}, {"indicator", header.step_indicator}}));
    PetscCall(f.WriteBlock("/time_step/eigenvector", H5T_NATIVE_DOUBLE, P, D, order.point_start, order.point_count, block.eigenvector.data()));
  }
  const hsize_t frames = header.field_frames.size() / 2;
  PetscCall(f.WriteBlock("/run/field_frames", H5T_NATIVE_DOUBLE, frames, 2, 0, rank == 0 ? frames : 0, header.field_frames.data()));
  PetscCall(f.Close());
  PetscFunctionReturn(0);
}

} // namespace

template <int D>
PetscErrorCode WriteCheckpoint(MPI_Comm comm, const std::string &path, const NaturalOrder &order, const Families &families,
                               CheckpointHeader *header, const CheckpointState &state)
{
  PetscMPIInt rank, size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  // Owned data -> this rank's natural block.
  PetscInt owned_points;
  PetscCall(PetscSFGetGraph(order.owned_points, nullptr, &owned_points, nullptr, nullptr));
  const std::size_t vectors = (std::size_t)D * order.point_count;
  CheckpointBlock   block;
  block.u.resize(vectors);
  block.v.resize(vectors);
  PetscCall(DoublesToNaturalOrder(order.owned_points, D, state.u, block.u.data()));
  PetscCall(DoublesToNaturalOrder(order.owned_points, D, state.v, block.v.data()));
  const std::size_t          owned_bonds = families.offsets[owned_points];
  std::vector<unsigned char> intact_local(owned_bonds);
  for (PetscInt i = 0; i < owned_points; ++i)
    for (std::size_t b = families.offsets[i]; b < families.offsets[i + 1]; ++b)
      intact_local[b] = state.bonds->is_intact((std::size_t)i, b - families.offsets[i]) ? 1 : 0;
  block.intact.resize(order.bond_count);
  PetscCall(ToNaturalOrder(order.owned_bonds, MPI_UNSIGNED_CHAR, intact_local.data(), block.intact.data()));
  header->dimension = D;
  header->has_c33   = state.c33 != nullptr;
  if (header->has_c33) {
    block.c33.resize(order.bond_count);
    PetscCall(ToNaturalOrder(order.owned_bonds, MPI_DOUBLE, state.c33, block.c33.data()));
  }
  header->has_damage = !state.bonds->damage.empty();
  if (header->has_damage) {
    block.damage.resize(order.bond_count);
    PetscCall(ToNaturalOrder(order.owned_bonds, MPI_DOUBLE, state.bonds->damage.data(), block.damage.data()));
  }
  block.family_size.assign(order.family_size.begin(), order.family_size.end());
  if (header->relaxation_records > 0) {
    block.relaxation_u.resize(vectors);
    block.relaxation_a.resize(vectors);
    PetscCall(DoublesToNaturalOrder(order.owned_points, D, state.relaxation_u, block.relaxation_u.data()));
    PetscCall(DoublesToNaturalOrder(order.owned_points, D, state.relaxation_a, block.relaxation_a.data()));
  }
  if (header->step_lambda > 0) {
    block.eigenvector.resize(vectors);
    PetscCall(DoublesToNaturalOrder(order.owned_points, D, state.step_eigenvector, block.eigenvector.data()));
  }
  PetscCall(BlockHash<D>(comm, order, block, &header->content_hash));
  header->content_hash += HeaderHash(*header);
  header->ranks = size;
  std::uint64_t text_hash = rank == 0 ? TextHash(*header) : 0; // rank 0's texts are the ones written
  PetscCallMPI(MPI_Bcast(&text_hash, 1, MPI_UINT64_T, 0, comm));

  const std::string tmp = path + ".tmp";
  PetscCall(WriteCheckpointFile<D>(comm, rank, tmp, order, *header, block, text_hash, state.step_eigenvector != nullptr));
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

template PetscErrorCode WriteCheckpoint<2>(MPI_Comm, const std::string &, const NaturalOrder &, const Families &, CheckpointHeader *,
                                           const CheckpointState &);
template PetscErrorCode WriteCheckpoint<3>(MPI_Comm, const std::string &, const NaturalOrder &, const Families &, CheckpointHeader *,
                                           const CheckpointState &);

} // namespace bapd
