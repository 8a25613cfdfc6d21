// The driver's body: the points, their families and partition, and each rank's share
// (SimulationD::BuildBody), on rank 0 or on every rank (-partition_type).
#include "bapd/solver/driver/simulation.hpp"

#include <cstdio>
#include <exception>
#include <string>

#include "bapd/core/geometry/geometry.hpp"
#include "bapd/core/geometry/lattice.hpp"
#include "bapd/core/kernel/patch_correction.hpp"
#include "bapd/solver/parallel/cloud_block.hpp"
#include "bapd/solver/parallel/distributed_body.hpp"
#include "bapd/solver/parallel/exchange.hpp"

namespace bapd {
namespace {

// Given points (2D or 3D) are not checked for pieces by the scene (FindCut looks at
// holes and notches on the lattice, body_pieces at the 3D lattice): here the bond graph
// itself is, per-point horizons and all. Writes "" if every point is bonded to the
// rest, else the message: how many pieces, the smallest one's size and a point of it
// (an isolated point has no stiffness at all; a loose piece moves freely).
template <int D> void DescribePieces(const PointCloud &cloud, const Families &fam, const std::string &source, char *message, std::size_t size)
{
  const std::size_t        n = fam.n_family;
  std::vector<std::size_t> parent(n);
  for (std::size_t i = 0; i < n; ++i) parent[i] = i;
  auto find = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) parent[find(i)] = find(static_cast<std::size_t>(fam.neighbour[b]));
  std::vector<std::size_t> count(n, 0);
  std::size_t              n_pieces = 0;
  for (std::size_t i = 0; i < n; ++i) n_pieces += count[find(i)]++ == 0;
  message[0] = '\0';
  if (n_pieces <= 1) return;
  std::size_t smallest = 0; // the first point of the smallest piece
  for (std::size_t i = 1; i < n; ++i)
    if (count[find(i)] < count[find(smallest)]) smallest = i;
  const std::string words = PiecesMessage(source, n_pieces, count[find(smallest)], cloud.natural_id[smallest], &cloud.x[D * smallest], D);
  std::snprintf(message, size, "%s", words.c_str());
}

// The families of points [0, n) of a cloud: the 2D notches' segments, or the 3D
// body's planar polygon notches, as the cut.
template <int D> Families BodyFamilies(const Scene &scene, const PointCloud &cloud, std::size_t n)
{
  if constexpr (D == 2) return build_families(cloud, n, scene.body.horizon(), scene.body.sheet.notches);
  else return nd::build_families<3>(cloud, n, scene.body.horizon(), nd::polygon_notches(scene.body.solid.notches));
}

// The body's points (rank 0): the geometry stage's in 2D (geometry.hpp); in 3D the
// lattice of its solids (one horizon, delta = factor dx), or the scene's clipped cloud
// (or centroids) with each point's own horizon, delta_i = factor cbrt(V_i), as 2D's
// given points get theirs (set_point_horizons, geometry.hpp).
template <int D> PointCloud BodyPoints(const Scene &scene)
{
  if constexpr (D == 2) return make_points(scene.body.sheet, scene.body.horizon_factor);
  else {
    if (!scene.body.solid.given_points) return nd::make_solid_points(scene.body.solid);
    PointCloud points = *scene.body.solid.given_points;
    set_point_horizons(&points, D, scene.body.horizon_factor, scene.body.sheet.thickness);
    return points;
  }
}

// This rank's share of the given points, natural ids [*first, *first + size) of the ones
// the body keeps: BodyPoints' points, with their own horizons, cut into blocks as
// ScatterBody cuts (BlockFirst). The scene holds every point (the file read whole).
template <int D> PointCloud GivenChunk(const Scene &scene, int rank, int size, PetscInt *first)
{
  PointCloud chunk;
  if constexpr (D == 2) {
    const Body<2>     &body  = scene.body.sheet;
    const GivenPoints &given = *body.given_points;
    const PetscInt     n     = (PetscInt)body_point_count(body);
    *first                   = BlockFirst(n, size, rank);
    const PetscInt last      = BlockFirst(n, size, rank + 1);
    PetscInt       id        = 0; // the natural id: the point's place among the kept (make_points)
    for (std::size_t p = 0; p < given.size() && id < last; ++p) {
      const double x = given.x[2 * p], y = given.x[2 * p + 1];
      if (!is_material(body, x, y)) continue;
      if (id >= *first) {
        chunk.natural_id.push_back(id);
        chunk.x.push_back(x), chunk.x.push_back(y);
        chunk.volume.push_back(given.volume[p]);
      }
      ++id;
    }
  } else {
    const PointCloud &given = *scene.body.solid.given_points;
    const PetscInt    n     = (PetscInt)given.size();
    *first                  = BlockFirst(n, size, rank);
    const PetscInt last     = BlockFirst(n, size, rank + 1);
    chunk.x.assign(given.x.begin() + 3 * *first, given.x.begin() + 3 * last);
    chunk.volume.assign(given.volume.begin() + *first, given.volume.begin() + last);
    chunk.natural_id.assign(given.natural_id.begin() + *first, given.natural_id.begin() + last);
  }
  set_point_horizons(&chunk, D, scene.body.horizon_factor, scene.body.sheet.thickness);
  return chunk;
}

// The whole body on rank 0 (global with family_volume and, with
// -force_patch_correction, the correction's numbers; the bond graph in CSR form,
// natural order), checked there (given points in pieces, the correction's solve) and
// against the memory with the real bond count; every rank stops together.
template <int D>
PetscErrorCode WholeBodyOnRankZero(MPI_Comm comm, const Scene &scene, PointCloud *global_out, std::vector<int> *offsets_out,
                                   std::vector<int> *neighbours_out)
{
  PointCloud       &global = *global_out;
  std::vector<int> &offsets = *offsets_out, &neighbours = *neighbours_out;
  int               patch_failed = 0, rank;
  char              pieces[512]  = ""; // rank 0: the message if given points fall apart

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    // Rank 0 builds the whole bond graph; fine up to a few 10^7 points (README). The
    // geometry stage gives the points: the lattice, or the given points with their
    // own volumes and horizons (geometry.hpp).
    global               = BodyPoints<D>(scene);
    Families all         = BodyFamilies<D>(scene, global, global.size());
    compute_family_volumes(global, all);
    // (a 3D lattice body in pieces was refused by the scene: make_solid_points)
    if (D == 2 && scene.body.sheet.given_points) DescribePieces<D>(global, all, scene.body.sheet.given_points->source, pieces, sizeof pieces);
    if (D == 3 && scene.body.solid.given_points) DescribePieces<D>(global, all, scene.body.solid.source, pieces, sizeof pieces);
    if (scene.material.patch_correction != PatchCorrection::off && !pieces[0]) { // per point, shipped with the points (patch_correction.hpp, layout.cpp)
      const bool            virial = scene.material.patch_correction == PatchCorrection::virial;
      PatchCorrectionReport report;
      try {
        global.patch_correction = virial ? compute_virial_patch_correction<D>(global, all, scene.material.stress_correction, &report)
                                         : compute_patch_correction<D>(global, all, scene.material.stress_correction, &report);
        global.patch_virial     = virial;
        PetscCall(PetscPrintf(PETSC_COMM_SELF, "%s", describe_patch_correction(report, virial).c_str()));
      } catch (const std::exception &e) {
        patch_failed = 1;
        PetscCall(PetscFPrintf(PETSC_COMM_SELF, stderr, "%s\n", e.what()));
      }
    }
    offsets.assign(all.offsets.begin(), all.offsets.end());
    neighbours.assign(all.neighbour.begin(), all.neighbour.end());
  }
  PetscCallMPI(MPI_Bcast(pieces, sizeof pieces, MPI_CHAR, 0, comm));
  PetscCheck(!pieces[0], comm, PETSC_ERR_USER, "%s", pieces);
  // The memory check with the real bond count (the scene's assumed the lattice's).
  int64_t counts[2] = {static_cast<int64_t>(global.size()), static_cast<int64_t>(offsets.empty() ? 0 : offsets.back())};
  PetscCallMPI(MPI_Bcast(counts, 2, MPI_INT64_T, 0, comm));
  PetscCall(CheckBodyMemory(comm, scene, counts[0], counts[1]));
  PetscCallMPI(MPI_Bcast(&patch_failed, 1, MPI_INT, 0, comm)); // every rank stops together
  PetscCheck(!patch_failed, comm, PETSC_ERR_USER,
             "-force_patch_correction %s: the affine patch correction could not be solved on these points (above); run "
             "with -force_patch_correction off", to_string(scene.material.patch_correction));
  PetscFunctionReturn(0);
}

} // namespace

// Body, partition, layout, families and reference bond geometry.
template <int D> PetscErrorCode SimulationD<D>::BuildBody()
{
  PointCloud         global;
  std::vector<int>   offsets, neighbours;
  const bool         parallel     = scene_.run.partition_type == PartitionType::ptscotch;
  const bool         given        = D == 2 ? (bool)scene_.body.sheet.given_points : (bool)scene_.body.solid.given_points;
  const FamilyBuilder families_of = [this](const PointCloud &cloud, std::size_t n) { return BodyFamilies<D>(scene_, cloud, n); };

  PetscFunctionBegin;
  PetscCall(PetscLogStagePush(stage_partition_));
  if (parallel && scene_.material.patch_correction == PatchCorrection::off) {
    // -partition_type ptscotch: every rank builds a slab of the lattice, or the families
    // of a slab of the given points, and no rank holds the whole bond graph
    // (distributed_body.hpp, cloud_block.hpp).
    BodyBlock block;
    if (given) {
      PetscInt         first;
      const PointCloud chunk  = GivenChunk<D>(scene_, rank_, size_, &first);
      const std::string source = D == 2 ? scene_.body.sheet.given_points->source : scene_.body.solid.source;
      PetscCall(CloudBlock<D>(comm_, chunk, first, families_of, source, &block));
    } else PetscCall(LatticeBlock<D>(comm_, scene_.body.sheet, scene_.body.solid, scene_.body.horizon(), families_of, &block));
    int64_t counts[2] = {static_cast<int64_t>(block.size()), static_cast<int64_t>(block.neighbours.size())};
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_INT64_T, MPI_SUM, comm_));
    PetscCall(CheckBodyMemory(comm_, scene_, counts[0], counts[1]));
    PetscCall(DistributeBlocks<D>(comm_, block, &layout_));
  } else {
    if (parallel) // the patch correction's solve runs over the whole body
      PetscCall(PetscPrintf(comm_, "Set-up: the body and its patch correction built on rank 0 (-partition_type ptscotch sets up the body on every rank without -force_patch_correction), partitioned by PT-Scotch\n"));
    PetscCall(WholeBodyOnRankZero<D>(comm_, scene_, &global, &offsets, &neighbours));
    if (parallel) {
      BodyBlock block;
      PetscCall(ScatterBody<D>(comm_, global, offsets, neighbours, &block));
      global = PointCloud(), offsets.clear(), neighbours.clear();
      PetscCall(DistributeBlocks<D>(comm_, block, &layout_));
    } else PetscCall(DistributePoints<D>(comm_, global, offsets, neighbours, &layout_));
  }
  PetscCall(PetscLogStagePop());

  // Every rank finds the same families for its owned and ring-1 points as rank 0
  // did: their whole neighbourhood lies in the two rings it holds.
  families_ = BodyFamilies<D>(scene_, layout_.cloud, (std::size_t)layout_.n_family());
  bond_state_ = BondState(families_);
  if (scene_.failure.enabled) {
    intact_before_ = bond_state_.intact; // sized once: a breaking pass copies into it
    released_points_.reserve((std::size_t)layout_.n_owned);
    released_terms_.assign((std::size_t)layout_.n_owned, 0.0);
    PetscCall(SetupCrackAxis());
  }
  // -force_stress_correction: C_i per family point, for the bond-only kernel only (the
  // energy-consistent form is stress-consistent as it is: stress_correction.hpp)
  geometry_.stress_correction =
      scene_.material.force_form == ForceForm::bond_only ? scene_.material.stress_correction : StressCorrection::none;
  nd::compute_bond_geometry<D>(layout_.cloud, families_, bond_state_, geometry_);

  PetscCall(force_.Setup<D>(comm_, scene_.material, layout_, families_, geometry_, bond_state_, stage_ghost_, stage_force_));
  if (scene_.failure.enabled)
    PetscCall(failure_.Setup(comm_, layout_, families_, scene_.failure.critical_stretch,
                             scene_.failure.tip_concentration * scene_.failure.fracture_energy, D, scene_.body.horizon(), scene_.body.sheet.thickness));
  if (scene_.failure.enabled) PetscCall(failure_.SetupSoftening(scene_.failure.softening, scene_.failure.fracture_energy, scene_.failure.fade_time,
                                                                  bond_state_));
  force_density_.assign(D * layout_.n_owned, 0.0);
  per_point_.assign(2 * layout_.n_owned, 0.0);
  point_energy_.assign(layout_.n_owned, 0.0);
  PetscInt bonds_local = (PetscInt)families_.offsets[layout_.n_owned], bonds_global = 0;
  PetscCallMPI(MPI_Allreduce(&bonds_local, &bonds_global, 1, MPIU_INT, MPI_SUM, comm_));
  PetscInt ghost_max = layout_.n_ghost(), owned_min = layout_.n_owned;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ghost_max, 1, MPIU_INT, MPI_MAX, comm_));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &owned_min, 1, MPIU_INT, MPI_MIN, comm_));
  PetscCall(PetscPrintf(comm_, "Body: %" PetscInt_FMT " points, %" PetscInt_FMT " bonds, %d rank(s); edge cut %" PetscInt_FMT ", fewest owned %" PetscInt_FMT ", most ghosts %" PetscInt_FMT "\n",
                        layout_.n_global, bonds_global, size_, layout_.edge_cut, owned_min, ghost_max));
  if (scene_.run.log_setup_memory) { // -log_setup_memory: the set-up's cost, every rank's peak so far
    double mine[2] = {MPI_Wtime() - wall_start_, PeakResidentBytes() / 1048576.0}, most[2], total;
    PetscCallMPI(MPI_Allreduce(mine, most, 2, MPI_DOUBLE, MPI_MAX, comm_));
    PetscCallMPI(MPI_Allreduce(&mine[1], &total, 1, MPI_DOUBLE, MPI_SUM, comm_));
    PetscCall(PetscPrintf(comm_, "Set-up: %.3f s (-partition_type %s); peak memory (VmHWM) largest rank %.1f MB, mean rank %.1f MB, rank 0 %.1f MB\n",
                          most[0], parallel ? "ptscotch" : "metis", most[1], total / size_, mine[1]));
  }
  PetscInt unusable = 0;
  for (PetscInt i = 0; i < layout_.n_owned; ++i)
    for (std::size_t q = 0; q < families_.size((std::size_t)i); ++q) unusable += !geometry_.is_usable((std::size_t)i, q);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &unusable, 1, MPIU_INT, MPI_SUM, comm_));
  if (unusable) PetscCall(PetscPrintf(comm_, "Bonds with a singular shape tensor (carry no force): %" PetscInt_FMT "\n", unusable));
  // Below delta = sqrt(2) dx every bond-associated family of a square lattice is
  // collinear: no bond carries force, and the stable-step estimate would fail with a
  // misleading message (docs/stability.md, section 6).
  char factor[32];
  std::snprintf(factor, sizeof factor, "%g", scene_.body.horizon_factor); // PETSc's %g would print "1."
  PetscCheck(bonds_global == 0 || unusable < bonds_global, comm_, PETSC_ERR_USER,
             "-horizon_factor %s: every bond's shape tensor is singular (its bond-associated family is collinear), so no bond "
             "carries force: raise -horizon_factor (at least 1.5; the paper uses 3.015)",
             factor);
  PetscFunctionReturn(0);
}

template PetscErrorCode SimulationD<2>::BuildBody();
template PetscErrorCode SimulationD<3>::BuildBody();

} // namespace bapd
