// Checkpoints: checking and reading one back (checkpoint.hpp has the format).
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "bapd/solver/io/checkpoint.hpp"
#include "bapd/solver/io/checkpoint_checksum.hpp"
#include "bapd/solver/io/hdf5_io.hpp"

namespace bapd {

namespace {

// Rank 0's text (MPI_CHAR) or numbers (MPI_DOUBLE), on every rank: its length, then it.
template <class Container>
PetscErrorCode Bcast(MPI_Comm comm, MPI_Datatype type, Container *values)
{
  PetscFunctionBegin;
  unsigned long long n = values->size();
  PetscCallMPI(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, comm));
  values->resize(n);
  if (n) PetscCallMPI(MPI_Bcast(values->data(), (int)n, type, 0, comm));
  PetscFunctionReturn(0);
}

// The first problem found: a damaged file names what is missing.
void Damaged(const std::string &path, const std::string &what, std::string &problem)
{
  if (problem.empty()) problem = "Checkpoint '" + path + "' is damaged: " + what + " (use an earlier checkpoint)";
}

// Rank 0: the attributes of the root and of /geometry (the step, time, run state and
// the geometry the checkpoint was written for).
void ReadRootAttributes(hid_t file, const std::string &path, CheckpointHeader *h, std::string &problem)
{
  auto damaged = [&](const std::string &what) { Damaged(path, what, problem); };
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

// Rank 0: the shapes of the arrays, the texts and tables of /run (checked against their
// checksum) and the optional sections (/relaxation, /time_step).
void ReadRunSections(hid_t file, const std::string &path, CheckpointHeader *h, std::string &problem)
{
  auto damaged = [&](const std::string &what) { Damaged(path, what, problem); };
  const hsize_t P = (hsize_t)h->geometry.points, B = (hsize_t)h->geometry.bonds, D = (hsize_t)h->dimension;
  // /bonds/c33 may be absent from a 3D file only (a run without the warm start).
  h->has_c33 = D == 2 || H5Lexists(file, "/bonds", H5P_DEFAULT) <= 0 || H5Lexists(file, "/bonds/c33", H5P_DEFAULT) > 0;
  // /bonds/damage: a run with -failure_softening (absent from every other file, and older ones).
  h->has_damage = H5Lexists(file, "/bonds", H5P_DEFAULT) > 0 && H5Lexists(file, "/bonds/damage", H5P_DEFAULT) > 0;
  if (h->has_damage && H5DatasetShape(file, "/bonds/damage") != std::vector<hsize_t>{B}) damaged("dataset /bonds/damage has the wrong shape");
  const struct {
    const char          *name;
    std::vector<hsize_t> shape;
  } expected[] = {{"/points/displacement", {P, D}}, {"/points/velocity", {P, D}}, {"/points/family_size", {P}},
                  {"/bonds/intact", {B}},         {"/bonds/c33", {B}}};
  for (const auto &e : expected)
    if ((h->has_c33 || std::strcmp(e.name, "/bonds/c33") != 0) && H5DatasetShape(file, e.name) != e.shape)
      damaged(std::string("dataset ") + e.name + " is missing or has the wrong shape");
  const std::vector<hsize_t> frames = H5DatasetShape(file, "/run/field_frames");
  if (frames.size() != 2 || frames[1] != 2) damaged("dataset /run/field_frames is missing or has the wrong shape");
  if (problem.empty() && !H5ReadText(file, "/run/options", &h->options)) damaged("dataset /run/options cannot be read");
  if (problem.empty() && !H5ReadText(file, "/run/history", &h->history)) damaged("dataset /run/history cannot be read");
  if (problem.empty() && !H5ReadText(file, "/run/static_states", &h->static_states)) damaged("dataset /run/static_states cannot be read");
  if (problem.empty() && !H5ReadDoubles(file, "/run/schedule_original", &h->schedule_original)) damaged("dataset /run/schedule_original cannot be read");
  if (problem.empty() && !H5ReadDoubles(file, "/run/schedule_current", &h->schedule_current)) damaged("dataset /run/schedule_current cannot be read");
  if (problem.empty() && h->schedule_original.size() != h->schedule_current.size()) damaged("the schedule datasets differ in length");
  if (problem.empty() && h->format_version >= 7 && !H5ReadDoubles(file, "/run/energy", &h->energy_totals))
    damaged("dataset /run/energy cannot be read");
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
      if (H5DatasetShape(file, name) != std::vector<hsize_t>{P, D}) damaged(std::string("dataset ") + name + " is missing or has the wrong shape");
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
    if (H5DatasetShape(file, "/time_step/eigenvector") != std::vector<hsize_t>{P, D})
      damaged("dataset /time_step/eigenvector is missing or has the wrong shape");
  }
}

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
  auto        damaged = [&](const std::string &what) { Damaged(path, what, problem); };
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
  // Version 6 on: the body's dimension; older files are 2D.
  if (problem.empty() && h->format_version >= 6 && !H5ReadAttribute(file, "/", "dimension", &h->dimension)) damaged("attribute dimension is missing");
  if (problem.empty() && h->dimension != 2 && h->dimension != 3)
    damaged("attribute dimension is " + std::to_string(h->dimension) + ", not 2 or 3");
  if (problem.empty()) ReadRootAttributes(file, path, h, problem);
  if (problem.empty()) ReadRunSections(file, path, h, problem);
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
  PetscCall(Bcast(comm, MPI_CHAR, &problem));
  PetscCheck(problem.empty(), comm, PETSC_ERR_FILE_UNEXPECTED, "%s", problem.c_str());
  long long     ints[14]  = {(long long)header->step,            (long long)header->ranks,
                             (long long)header->geometry.points, (long long)header->geometry.bonds,
                             (long long)header->format_version,  (long long)header->static_hold_done,
                             (long long)header->relaxation_records, (long long)header->step_next_estimate,
                             (long long)header->step_by_stiffness,  (long long)header->step_by_travel,
                             (long long)header->step_interval_now,  (long long)header->dimension,
                             (long long)header->has_c33,         (long long)header->has_damage};
  double        reals[13] = {header->time,        header->time_step,         header->stretch, header->geometry.dx,
                             header->geometry.horizon, header->end_time_original, header->end_time,
                             header->step_lambda, header->step_stiffness_dt, header->step_shortest, header->step_stretch,
                             header->step_stretch_increment, header->step_indicator};
  std::uint64_t hashes[2] = {header->content_hash, header->geometry.hash};
  PetscCallMPI(MPI_Bcast(ints, 14, MPI_LONG_LONG, 0, comm));
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
  header->dimension          = ints[11];
  header->has_c33            = ints[12] != 0;
  header->has_damage         = ints[13] != 0;
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
  PetscCall(Bcast(comm, MPI_CHAR, &header->reason));
  PetscCall(Bcast(comm, MPI_CHAR, &header->options));
  PetscCall(Bcast(comm, MPI_CHAR, &header->history));
  PetscCall(Bcast(comm, MPI_CHAR, &header->static_states));
  PetscCall(Bcast(comm, MPI_DOUBLE, &header->field_frames));
  PetscCall(Bcast(comm, MPI_DOUBLE, &header->schedule_original));
  PetscCall(Bcast(comm, MPI_DOUBLE, &header->schedule_current));
  PetscCall(Bcast(comm, MPI_DOUBLE, &header->energy_totals));
  PetscFunctionReturn(0);
}

template <int D>
PetscErrorCode ReadCheckpointState(MPI_Comm comm, const std::string &path, const NaturalOrder &order,
                                   const Families &families, const CheckpointHeader &header,
                                   const GeometryFingerprint &geometry, const CheckpointState &state)
{
  PetscFunctionBegin;
  // Its dimension first: a body of the other dimension is another body, but "the
  // same dimension" is the fix to name.
  PetscCheck(header.dimension == D, comm, PETSC_ERR_USER,
             "Checkpoint '%s' holds a %lldD body and this scene is %dD: a run continues only in the dimension that wrote it. "
             "Restart with the scene that wrote it: its options are stored in the checkpoint and apply unless the command line overrides them",
             path.c_str(), (long long)header.dimension, D);
  const GeometryFingerprint &g = header.geometry;
  // The hash covers the positions and every family: equal, the body is this one, and a
  // dx or horizon that differs is a damaged attribute (no checksum covers them) or a
  // scene that changed only the number (a bit flip read as "another body").
  PetscCheck(g.hash != geometry.hash || g.points != geometry.points || g.bonds != geometry.bonds || SameGeometry(g, geometry), comm,
             PETSC_ERR_USER,
             "Checkpoint '%s' holds this body's points and bonds, but its attributes say dx %.17g m and horizon %.17g m where this "
             "scene has %.17g m and %.17g m: an attribute damaged (restart from an earlier checkpoint), or a scene that changed "
             "the horizon without changing a family (restart with the scene that wrote it)",
             path.c_str(), g.dx, g.horizon, geometry.dx, geometry.horizon);
  PetscCheck(SameGeometry(g, geometry), comm, PETSC_ERR_USER,
             "Checkpoint '%s' belongs to another body: it holds %lld points and %lld bonds (dx %g m, horizon %g m), this scene "
             "%lld points and %lld bonds (dx %g m, horizon %g m)%s. Restart with the scene that wrote it: its options are "
             "stored in the checkpoint and apply unless the command line overrides them",
             path.c_str(), (long long)g.points, (long long)g.bonds, g.dx, g.horizon, (long long)geometry.points,
             (long long)geometry.bonds, geometry.dx, geometry.horizon,
             g.points == geometry.points && g.bonds == geometry.bonds && g.dx == geometry.dx && g.horizon == geometry.horizon
               ? " and the same counts but other positions, holes or notches"
               : "");
  const std::size_t vectors = (std::size_t)D * order.point_count;
  CheckpointBlock   block;
  block.u.resize(vectors);
  block.v.resize(vectors);
  block.family_size.resize(order.point_count);
  block.intact.resize(order.bond_count);
  if (header.has_c33) block.c33.resize(order.bond_count);
  if (header.has_damage) block.damage.resize(order.bond_count);
  if (header.relaxation_records > 0) block.relaxation_u.resize(vectors), block.relaxation_a.resize(vectors);
  if (header.step_lambda > 0) block.eigenvector.resize(vectors);
  {
    H5ParallelFile f;
    const hsize_t  P = (hsize_t)order.n_points, B = (hsize_t)order.n_bonds;
    PetscCall(f.Open(comm, path));
    PetscCall(f.ReadBlock("/points/displacement", H5T_NATIVE_DOUBLE, P, D, order.point_start, order.point_count, block.u.data()));
    PetscCall(f.ReadBlock("/points/velocity", H5T_NATIVE_DOUBLE, P, D, order.point_start, order.point_count, block.v.data()));
    PetscCall(f.ReadBlock("/points/family_size", H5T_NATIVE_INT32, P, 0, order.point_start, order.point_count, block.family_size.data()));
    PetscCall(f.ReadBlock("/bonds/intact", H5T_NATIVE_UCHAR, B, 0, order.bond_start, order.bond_count, block.intact.data()));
    if (header.has_c33) PetscCall(f.ReadBlock("/bonds/c33", H5T_NATIVE_DOUBLE, B, 0, order.bond_start, order.bond_count, block.c33.data()));
    if (header.has_damage)
      PetscCall(f.ReadBlock("/bonds/damage", H5T_NATIVE_DOUBLE, B, 0, order.bond_start, order.bond_count, block.damage.data()));
    if (header.relaxation_records > 0) {
      PetscCall(f.ReadBlock("/relaxation/displacement", H5T_NATIVE_DOUBLE, P, D, order.point_start, order.point_count, block.relaxation_u.data()));
      PetscCall(f.ReadBlock("/relaxation/acceleration", H5T_NATIVE_DOUBLE, P, D, order.point_start, order.point_count, block.relaxation_a.data()));
    }
    if (header.step_lambda > 0)
      PetscCall(f.ReadBlock("/time_step/eigenvector", H5T_NATIVE_DOUBLE, P, D, order.point_start, order.point_count, block.eigenvector.data()));
    PetscCall(f.Close());
  }
  std::uint64_t hash = 0;
  PetscCall(BlockHash<D>(comm, order, block, &hash));
  hash += HeaderHash(header);
  PetscCheck(hash == header.content_hash, comm, PETSC_ERR_FILE_UNEXPECTED,
             "Checkpoint '%s' is corrupt: its data do not match the checksum written with them (use an earlier checkpoint)", path.c_str());

  // Block -> layout: u, v of owned points; bond bits and C33 of every family point
  // (ring-1 ghosts take their owner's values, as after every breaking pass).
  PetscCall(DoublesFromNaturalOrder(order.owned_points, D, block.u.data(), state.u));
  PetscCall(DoublesFromNaturalOrder(order.owned_points, D, block.v.data(), state.v));
  if (header.relaxation_records > 0 && state.relaxation_u) {
    PetscCall(DoublesFromNaturalOrder(order.owned_points, D, block.relaxation_u.data(), state.relaxation_u));
    PetscCall(DoublesFromNaturalOrder(order.owned_points, D, block.relaxation_a.data(), state.relaxation_a));
  }
  if (header.step_lambda > 0 && state.step_eigenvector)
    PetscCall(DoublesFromNaturalOrder(order.owned_points, D, block.eigenvector.data(), state.step_eigenvector));
  const std::size_t          family_bonds = families.offsets[families.n_family];
  std::vector<unsigned char> intact_local(family_bonds);
  PetscCall(FromNaturalOrder(order.family_bonds, MPI_UNSIGNED_CHAR, block.intact.data(), intact_local.data()));
  if (state.c33 && header.has_c33) PetscCall(FromNaturalOrder(order.family_bonds, MPI_DOUBLE, block.c33.data(), state.c33));
  else if (state.c33) std::fill(state.c33, state.c33 + family_bonds, 0.0); // none stored: the cold start
  BondState        &bs = *state.bonds;
  PetscCheck(header.has_damage == !bs.damage.empty(), comm, PETSC_ERR_USER,
             "Checkpoint '%s' was written %s -failure_softening and this run is %s it: restart with the run's own "
             "-failure_softening (its bonds' damage is part of the state)",
             path.c_str(), header.has_damage ? "with" : "without", bs.damage.empty() ? "without" : "with");
  if (header.has_damage) PetscCall(FromNaturalOrder(order.family_bonds, MPI_DOUBLE, block.damage.data(), bs.damage.data()));
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

template PetscErrorCode ReadCheckpointState<2>(MPI_Comm, const std::string &, const NaturalOrder &, const Families &,
                                               const CheckpointHeader &, const GeometryFingerprint &, const CheckpointState &);
template PetscErrorCode ReadCheckpointState<3>(MPI_Comm, const std::string &, const NaturalOrder &, const Families &,
                                               const CheckpointHeader &, const GeometryFingerprint &, const CheckpointState &);

} // namespace bapd
