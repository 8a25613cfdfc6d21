#include "bapd/solver/driver/simulation.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <exception>
#include <filesystem>
#include <limits>

#include "bapd/solver/driver/static_solver.hpp"
#include "bapd/solver/input/help.hpp"
#include "bapd/core/geometry/geometry.hpp"
#include "bapd/core/kernel/patch_correction.hpp"
#include "bapd/solver/parallel/distributed_body.hpp"

namespace bapd {

template <int D> SimulationD<D>::~SimulationD()
{
  TSDestroy(&ts_);
  ISDestroy(&is_position_);
  ISDestroy(&is_momentum_);
  VecDestroy(&X_);
}

namespace {
// The driver's -log_view stages, one set per process for both dimensions.
PetscErrorCode LogStages(const PetscLogStage **stages)
{
  static PetscLogStage registered[6];
  static bool          done = false;

  PetscFunctionBegin;
  if (!done) {
    const char *names[6] = {"Setup", "Partition", "Force", "Ghost exchange", "Time step", "Output"};
    for (int k = 0; k < 6; ++k) PetscCall(PetscLogStageRegister(names[k], &registered[k]));
    done = true;
  }
  *stages = registered;
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode ReadScene(MPI_Comm comm, Scene *scene)
{
  PetscFunctionBegin;
  PetscCall(CheckpointMergeOptions(comm)); // -restart FILE: the checkpoint's options are the defaults
  PetscCall(SceneFromOptions(comm, scene));
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::Setup()
{
  Scene scene;

  PetscFunctionBegin;
  PetscCall(ReadScene(comm_, &scene));
  PetscCall(Setup(std::move(scene)));
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::Setup(Scene scene)
{
  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank_));
  PetscCallMPI(MPI_Comm_size(comm_, &size_));
  // -log_view stages, registered once per process (a test may build several runs, of
  // either dimension).
  const PetscLogStage *stages;
  PetscCall(LogStages(&stages));
  stage_setup_ = stages[0], stage_partition_ = stages[1], stage_force_ = stages[2];
  stage_ghost_ = stages[3], stage_step_ = stages[4], stage_output_ = stages[5];
  wall_start_ = MPI_Wtime();

  PetscCall(PetscLogStagePush(stage_setup_));
  scene_ = std::move(scene);
  paths_ = OutputPaths(scene_.output_dir);
  PetscCheck(scene_.help_only || scene_.dimension == D, comm_, PETSC_ERR_PLIB,
             "SimulationD<%d> was given a scene of dimension %d: build the driver of the scene's dimension (main.cpp)", D, scene_.dimension);
  PetscCall(ReadOutputOptions()); // -output_fields..., -checkpoint_..., -restart
  PetscCall(RelaxationFromOptions(comm_, &relaxation_kind_)); // -relaxation
  PetscCall(TimeStepOptionsFromOptions(comm_, &time_step_options_)); // -time_step_reestimate ...
  if (scene_.help_only) {
    // -help all: list the time stepper's options too (PETSc's), and stop.
    if (CurrentHelpMode() != HelpMode::bapd) {
      PetscCall(TSCreate(comm_, &ts_));
      PetscCall(TSSetType(ts_, TSBASICSYMPLECTIC));
      PetscCall(TSSetFromOptions(ts_));
    }
    PetscCall(PetscLogStagePop());
    PetscFunctionReturn(0);
  }
  PetscCall(CheckOptionsEarly());
  PetscCall(StaticSolverCheckScene(comm_, scene_, output_.checkpoint)); // -solver static: what it refuses
  PetscCall(SceneView(comm_, scene_));
  PetscCall(ClaimOutputDirectory()); // before anything is written: locked; a restart's newer results
  PetscCall(BuildBody());
  PetscCall(loading_.Setup(comm_, scene_, layout_));
  PetscCall(BuildProbes());
  last_reaction_.assign(D * scene_.loads.size(), 0.0);
  last_probe_u_.assign(D * scene_.probes.size(), 0.0);
  grip_u_.assign(D * scene_.loads.size(), 0.0);
  {
    std::size_t most = 0;
    for (const LoadSetPoints &set : loading_.load_set_points()) most = std::max(most, set.points.size());
    grip_terms_.assign(D * most, 0.0);
  }
  // -solver static takes no time step: the stable-step estimate (a Krylov search of 10-60
  // force evaluations) and the relaxation are the dynamic route's alone. The TS is still
  // made (it holds the state and the time that the output reads) but never stepped.
  if (scene_.solver != SolverKind::static_newton) {
    PetscCall(step_control_.EstimateStable(comm_, scene_, time_step_options_, layout_, loading_, force_));
    PetscCall(SetupRelaxation());
  }
  PetscCall(SetupTimeStepper());
  PetscCall(budget_.Setup(loading_, layout_, scene_.density, scene_.loads.size()));
  {
    const double *x;
    PetscCall(VecGetArrayRead(X_, &x));
    PetscCall(budget_.Start(comm_, x + D * layout_.n_owned)); // the grips' speeds at t = 0
    PetscCall(VecRestoreArrayRead(X_, &x));
  }
  // The rows by load: every end time / -output_history_rows of simulated time, the end
  // time as the scene gives it (before a restart or an ended hold moves it), so that a
  // continuation writes the rows the uninterrupted run writes.
  const double history_end = loading_.end_time_original() > 0 ? loading_.end_time_original() : loading_.schedule().end_time();
  const double history_period = scene_.output_history_rows > 0 ? history_end / (double)scene_.output_history_rows : 0.0;
  history_.Setup(scene_, paths_);
  history_.StartRowsByLoad(history_period, 0.0); // (HistoryReport::Restore reads its period)
  PetscCall(OpenHistory());
  PetscCall(SetupOutput()); // restores the state with -restart
  {
    PetscReal t;
    PetscCall(TSGetTime(ts_, &t));
    history_.StartRowsByLoad(history_period, t);
    PetscCall(SetupObservers(t)); // history, fields, checkpoints, progress from t on
  }
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(0);
}

// Every option is checked before any work (docs/options.md): the time stepper's on a
// throw-away TS (a bad -ts_type or -ts_max_steps value fails here, not after the body
// and the stable step are built), then an option nothing read (a typo) is refused.
template <int D> PetscErrorCode SimulationD<D>::CheckOptionsEarly()
{
  TS     probe;
  TSType type = nullptr;

  PetscFunctionBegin;
  PetscCall(TSCreate(comm_, &probe));
  PetscErrorCode ierr = TSSetType(probe, TSBASICSYMPLECTIC);
  if (!ierr) ierr = TSSetFromOptions(probe);
  std::string type_name;
  if (!ierr) ierr = TSGetType(probe, &type);
  if (!ierr && type) type_name = type;
  PetscCall(TSDestroy(&probe));
  PetscCall(ierr);
  // The dynamics are explicit: the TS gets right-hand sides only (u' = v, v' = a(u)),
  // no implicit function and no Jacobian, and the step control (the stable step, the
  // re-estimates, the travel limit) assumes an explicit scheme. An implicit type would
  // fail inside its first nonlinear solve, or never end it.
  static const char *const explicit_types[] = {TSBASICSYMPLECTIC, TSEULER, TSRK, TSSSP};
  bool supported = false;
  for (const char *t : explicit_types) supported |= type_name == t;
  // -ts_max_time would end the run before -end_time (a result far short of the load
  // asked for, reported as finished) or let it run past it: the run's length is bapd's.
  PetscBool max_time = PETSC_FALSE;
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-ts_max_time", &max_time));
  PetscCheck(!max_time, comm_, PETSC_ERR_USER,
             "-ts_max_time is not read: the run's length is -end_time (default: the end of -load_schedule). Remove -ts_max_time and "
             "give -end_time instead (or -end_step N to stop after step N)");
  PetscCheck(supported, comm_, PETSC_ERR_USER,
             "-ts_type %s is not supported: bapd integrates its equations of motion with an explicit time stepper (it gives PETSc "
             "the right-hand side only, no Jacobian, and its step control assumes an explicit scheme). Use basicsymplectic "
             "(velocity Verlet, the default: leave -ts_type out), rk, euler or ssp",
             type_name.c_str());
  PetscCall(CheckUnusedOptions(comm_));
  PetscFunctionReturn(0);
}

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
  const double *x = &cloud.x[D * smallest];
  char          at[96];
  if (D == 2) std::snprintf(at, sizeof at, "(%g, %g)", x[0], x[1]);
  else std::snprintf(at, sizeof at, "(%g, %g, %g)", x[0], x[1], x[2]);
  std::snprintf(message, size,
                "%s: the given points fall apart into %zu pieces with no bond between them (the smallest: %zu point(s), e.g. "
                "point %lld at %s m): a piece not bonded to the rest has no stiffness against it. Remove the "
                "stray points from the file, close the gap, or raise -horizon_factor",
                source.c_str(), n_pieces, count[find(smallest)], static_cast<long long>(cloud.natural_id[smallest]), at);
}

// The families of points [0, n) of a cloud: the 2D notches' segments, or the 3D
// body's planar polygon notches, as the cut.
template <int D> Families BodyFamilies(const Scene &scene, const PointCloud &cloud, std::size_t n)
{
  if constexpr (D == 2) return build_families(cloud, n, scene.horizon(), scene.body.notches);
  else return nd::build_families<3>(cloud, n, scene.horizon(), nd::polygon_notches(scene.body3d.solid.notches));
}

// The body's points (rank 0): the geometry stage's in 2D (geometry.hpp); in 3D the
// lattice of its solids (one horizon, delta = factor dx), or the scene's clipped cloud
// (or centroids) with each point's own horizon, delta_i = factor cbrt(V_i), as 2D's
// given points get theirs (set_point_horizons, geometry.hpp).
template <int D> PointCloud BodyPoints(const Scene &scene)
{
  if constexpr (D == 2) return make_points(scene.body, scene.horizon_factor);
  else {
    if (!scene.body3d.given_points) return nd::make_solid_points(scene.body3d.solid);
    PointCloud points = *scene.body3d.given_points;
    set_point_horizons(&points, D, scene.horizon_factor, scene.body.thickness);
    return points;
  }
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
    if (D == 2 && scene.body.given_points) DescribePieces<D>(global, all, scene.body.given_points->source, pieces, sizeof pieces);
    if (D == 3 && scene.body3d.given_points) DescribePieces<D>(global, all, scene.body3d.source, pieces, sizeof pieces);
    if (scene.patch_correction != PatchCorrection::off && !pieces[0]) { // per point, shipped with the points (patch_correction.hpp, layout.cpp)
      const bool            virial = scene.patch_correction == PatchCorrection::virial;
      PatchCorrectionReport report;
      try {
        global.patch_correction = virial ? compute_virial_patch_correction<D>(global, all, scene.stress_correction, &report)
                                         : compute_patch_correction<D>(global, all, scene.stress_correction, &report);
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
             "with -force_patch_correction off", to_string(scene.patch_correction));
  PetscFunctionReturn(0);
}

} // namespace

// Body, partition, layout, families and reference bond geometry.
template <int D> PetscErrorCode SimulationD<D>::BuildBody()
{
  PointCloud         global;
  std::vector<int>   offsets, neighbours;
  const bool         parallel     = scene_.partition_type == PartitionType::ptscotch;
  const bool         given        = D == 2 ? (bool)scene_.body.given_points : (bool)scene_.body3d.given_points;
  const FamilyBuilder families_of = [this](const PointCloud &cloud, std::size_t n) { return BodyFamilies<D>(scene_, cloud, n); };

  PetscFunctionBegin;
  PetscCall(PetscLogStagePush(stage_partition_));
  if (parallel && !given && scene_.patch_correction == PatchCorrection::off) {
    // -partition_type ptscotch on a lattice: every rank builds a slab of it, and no
    // rank holds the whole body or bond graph (distributed_body.hpp).
    BodyBlock block;
    PetscCall(LatticeBlock<D>(comm_, scene_.body, scene_.body3d.solid, scene_.horizon(), families_of, &block));
    int64_t counts[2] = {static_cast<int64_t>(block.size()), static_cast<int64_t>(block.neighbours.size())};
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_INT64_T, MPI_SUM, comm_));
    PetscCall(CheckBodyMemory(comm_, scene_, counts[0], counts[1]));
    PetscCall(DistributeBlocks<D>(comm_, block, &layout_));
  } else {
    if (parallel) // given points, or the patch correction's solve over the whole body
      PetscCall(PetscPrintf(comm_, "Set-up: %s built on rank 0 (-partition_type ptscotch sets up a lattice body on every rank), partitioned by PT-Scotch\n",
                            given ? "the given points" : "the body and its patch correction"));
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
  if (scene_.failure) {
    intact_before_ = bond_state_.intact; // sized once: a breaking pass copies into it
    released_points_.reserve((std::size_t)layout_.n_owned);
    released_terms_.assign((std::size_t)layout_.n_owned, 0.0);
    PetscCall(SetupCrackAxis());
  }
  // -force_stress_correction: C_i per family point, for the bond-only kernel only (the
  // energy-consistent form is stress-consistent as it is: stress_correction.hpp)
  geometry_.stress_correction =
      scene_.force_form == ForceForm::bond_only ? scene_.stress_correction : StressCorrection::none;
  nd::compute_bond_geometry<D>(layout_.cloud, families_, bond_state_, geometry_);

  PetscCall(force_.Setup<D>(comm_, scene_, layout_, families_, geometry_, bond_state_, stage_ghost_, stage_force_));
  if (scene_.failure)
    PetscCall(failure_.Setup(comm_, layout_, families_, scene_.critical_stretch,
                             scene_.tip_concentration * scene_.fracture_energy, D, scene_.horizon(), scene_.body.thickness));
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
  if (scene_.log_setup_memory) { // -log_setup_memory: the set-up's cost, every rank's peak so far
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
  std::snprintf(factor, sizeof factor, "%g", scene_.horizon_factor); // PETSc's %g would print "1."
  PetscCheck(bonds_global == 0 || unusable < bonds_global, comm_, PETSC_ERR_USER,
             "-horizon_factor %s: every bond's shape tensor is singular (its bond-associated family is collinear), so no bond "
             "carries force: raise -horizon_factor (at least 1.5; the paper uses 3.015)",
             factor);
  PetscFunctionReturn(0);
}

// Each probe reads the point ProbeLocate picks (scene.hpp: nearest, ties to the
// lowest natural id, so the same point on any layout).
template <int D> PetscErrorCode SimulationD<D>::BuildProbes()
{
  PetscFunctionBegin;
  probes_.assign(scene_.probes.size(), {});
  for (std::size_t p = 0; p < scene_.probes.size(); ++p) {
    ProbeLocation where;
    PetscCall(ProbeLocate<D>(comm_, scene_.probes[p], layout_.cloud.x.data(), layout_.cloud.natural_id.data(), layout_.n_owned, &where));
    ProbePoint &pp = probes_[p];
    pp.natural_id  = where.natural_id;
    pp.owner_rank  = where.owner;
    pp.local_index = where.local_index;
    double xyz[3]  = {0, 0, 0};
    if (where.owner == rank_)
      for (int c = 0; c < D; ++c) xyz[c] = layout_.cloud.x[D * where.local_index + c];
    PetscCallMPI(MPI_Bcast(xyz, D, MPI_DOUBLE, where.owner, comm_));
    pp.x = xyz[0], pp.y = xyz[1], pp.z = xyz[2];
    if (D == 2)
      PetscCall(PetscPrintf(comm_, "Probe %s: point %lld at (%g, %g) m\n", scene_.probes[p].name.c_str(), (long long)pp.natural_id, pp.x, pp.y));
    else
      PetscCall(PetscPrintf(comm_, "Probe %s: point %lld at (%g, %g, %g) m\n", scene_.probes[p].name.c_str(), (long long)pp.natural_id, pp.x, pp.y,
                            pp.z));
  }
  PetscFunctionReturn(0);
}

// -relaxation adaptive: the damping coefficient follows the slowest mode (relaxation.hpp).
template <int D> PetscErrorCode SimulationD<D>::SetupRelaxation()
{
  PetscFunctionBegin;
  const double stable_dt = step_control_.stable();
  relaxation_.Setup(relaxation_kind_, (std::size_t)layout_.n_owned, layout_.cloud.volume.data(), loading_.held_dofs(), scene_.damping,
                    stable_dt);
  if (relaxation_.active()) {
    char range[96]; // PETSc's %g would print "50."
    std::snprintf(range, sizeof range, "between %g (-damping) and %.4g 1/s", scene_.damping, 4.0 / stable_dt);
    PetscCall(PetscPrintf(comm_, "Relaxation: adaptive, damping c = 2 omega every step (Rayleigh quotient of the latest increment), %s\n", range));
    // With bonds breaking, the state depends on the loading path and on the dynamics:
    // a route that shortcuts both answers another question.
    if (scene_.failure)
      PetscCall(PetscFPrintf(comm_, PETSC_STDERR,
                             "bapd: warning: -relaxation adaptive with failure (-failure_critical_stretch): the fast route assumes a "
                             "static state that does not depend on the loading path, which breaking bonds make false; use it "
                             "for runs without failure\n"));
  }
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::PostStep(TS ts)
{
  SimulationD *sim;
  PetscInt    step;
  PetscReal   t;
  Vec         X;
  double     *x;

  PetscFunctionBegin;
  PetscCall(TSGetApplicationContext(ts, &sim));
  PetscCall(TSGetStepNumber(ts, &step));
  PetscCall(TSGetTime(ts, &t));
  PetscCall(TSGetSolution(ts, &X));
  const PetscInt n = D * sim->layout_.n_owned;
  PetscCall(VecGetArray(X, &x));
  double damping = sim->scene_.damping;
  PetscCall(sim->relaxation_.Damping(sim->comm_, &damping)); // -relaxation adaptive: recomputed every step
  // Mass-proportional damping, integrated exactly over the step (operator split):
  // works with every TS type and never destabilises the step. The grips' speeds
  // are set again just below.
  const double decay = damping > 0 ? std::exp(-damping * sim->step_control_.current()) : 1.0;
  sim->budget_.Damp(x + n, decay); // (also without damping: the grips' speeds before they are set)
  if (damping > 0)
    for (PetscInt k = 0; k < n; ++k) x[n + k] *= decay;
  sim->loading_.Apply(t, x, x + n);
  PetscCall(sim->budget_.EndStep(sim->comm_, x, x + n));
  PetscCall(VecRestoreArray(X, &x));

  PetscBool diverged = PETSC_FALSE;
  PetscCall(sim->CheckHealth(step, t, &diverged));
  if (!diverged) {
    // A state outside the law's validity (the chain limit reached in I1): the run is not
    // unstable, its stress is no longer the material's. The message is whole; the last
    // good state is saved as for a divergence.
    std::string invalid;
    PetscCall(sim->CheckLawValidity(step, t, &invalid));
    if (!invalid.empty()) {
      sim->stop_reason_ = invalid, sim->stopped_on_error_ = true;
      PetscCall(sim->OutputOnDivergence());
      PetscCall(TSSetConvergedReason(ts, TS_DIVERGED_NONLINEAR_SOLVE));
      PetscFunctionReturn(0);
    }
  }
  if (!diverged) {
    // Runaway energy: an unstable time step caught before NaN or shattering (divergence.hpp).
    std::string runaway;
    PetscCall(sim->CheckRunaway(step, t, &runaway));
    if (!runaway.empty()) sim->stop_reason_ = runaway, sim->stopped_on_error_ = true, diverged = PETSC_TRUE;
  }
  if (diverged) {
    PetscCall(sim->DiagnoseDivergence()); // the cause, from the last good state
    PetscCall(sim->OutputOnDivergence()); // checkpoint of the last good state
    PetscCall(TSSetConvergedReason(ts, TS_DIVERGED_NONLINEAR_SOLVE));
    PetscFunctionReturn(0);
  }
  bool broke = false; // bonds broke on some rank in this step (BreakFurther)
  if (sim->scene_.failure) {
    PetscCall(VecGetArray(X, &x));
    PetscCall(sim->force_.UpdatePositions(x));
    PetscCall(VecRestoreArray(X, &x));
    if (sim->failure_.by_energy()) sim->force_.BondEnergies(sim->failure_.bond_energies());
    std::copy(sim->bond_state_.intact.begin(), sim->bond_state_.intact.end(), sim->intact_before_.begin());
    PetscCall(sim->failure_.Break(sim->force_.positions(), sim->force_.failed_bonds(), sim->bond_state_, sim->geometry_));
    PetscCall(sim->BreakFurther(&broke));
    double released;
    PetscCall(sim->ReleasedEnergy(broke, &released));
    sim->budget_.Release(released);
  }
  {
    // Before any checkpoint: a restart takes the same next step (re-estimated about the
  // latest evaluation when due, shortened while points fly: time_step_control.hpp).
    const double *xr;
    PetscCall(VecGetArrayRead(X, &xr));
    PetscCall(sim->step_control_.AfterStep(sim->comm_, step, sim->loading_.stretch_at(t), sim->layout_, sim->families_, sim->bond_state_, sim->force_, xr + n,
                                           sim->scene_.failure ? &sim->failure_.touched() : nullptr, broke, ts));
    PetscCall(VecRestoreArrayRead(X, &xr));
    sim->relaxation_.FollowStableStep(sim->step_control_.stable_now()); // its cap, 2 omega_max
  }
  // The reporting (a row, a file or a line only reads the state: the results stay the
  // same bits): history.csv and the static-hold test, field files, checkpoints and
  // SIGTERM/SIGINT, progress lines (run_observer.hpp).
  PetscCall(sim->Report(step, t));
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::Run()
{
  PetscFunctionBegin;
  if (scene_.help_only) PetscFunctionReturn(0);
  if (scene_.solver == SolverKind::static_newton) { // static states by Newton (static_solver.hpp)
    StaticSolver<D> solver(*this);
    PetscCall(solver.Setup());
    PetscCall(solver.Run());
    PetscFunctionReturn(0);
  }
  PetscCall(PetscLogStagePush(stage_step_));
  PetscCall(TSSolve(ts_, X_));
  PetscCall(PetscLogStagePop());
  PetscInt  step;
  PetscReal t;
  PetscCall(TSGetStepNumber(ts_, &step));
  PetscCall(TSGetTime(ts_, &t));
  std::string cut_short;
  if (!stopped_on_error_) PetscCall(StoppedShort(step, t, &cut_short));
  if (history_.last_step() != step && !stopped_on_error_) PetscCall(WriteHistoryRow(step, t)); // the end-of-run row
  PetscCall(OutputAtEnd(step, t)); // the last field file (and checkpoint)
  if (scene_.output_final_state) PetscCall(WriteFinalState());
  // Stopped short of the end time by a PETSc limit: everything a normal end writes is
  // written (above), and then the run fails (below), so that no script takes it for whole.
  if (!cut_short.empty()) stop_reason_ = cut_short, stopped_on_error_ = true;
  PetscCall(Summary());
  PetscCheck(!stopped_on_error_, comm_, PETSC_ERR_NOT_CONVERGED, "%s", stop_reason_.c_str());
  PetscFunctionReturn(0);
}

// The TS stopped at its step limit before the end time: after -end_step (on purpose:
// a note, exit 0), or at -ts_max_steps (PETSc's limit, maybe from a checkpoint's
// options: *message says so, and the run fails). TS_EXACTFINALTIME_MATCHSTEP lands the
// last step on the end time; a run within 1e-9 of it is whole.
template <int D> PetscErrorCode SimulationD<D>::StoppedShort(PetscInt step, double t, std::string *message)
{
  TSConvergedReason reason;
  PetscReal         end;
  PetscInt          max_steps;

  PetscFunctionBegin;
  message->clear();
  PetscCall(TSGetConvergedReason(ts_, &reason));
  PetscCall(TSGetMaxTime(ts_, &end));
  PetscCall(TSGetMaxSteps(ts_, &max_steps));
  if (reason != TS_CONVERGED_ITS || !(end - t > 1e-9 * end)) PetscFunctionReturn(0);
  if (scene_.end_step >= 0 && step >= scene_.end_step) {
    PetscCall(PetscPrintf(comm_, "\nStopped after step %" PetscInt_FMT " (-end_step), at t = %.6e s of the end time %.6e s%s\n", step, t, end,
                          output_.checkpoint.periodic() ? ": continue with -restart and a later -end_step (or -end_step -1)" : ""));
    PetscFunctionReturn(0);
  }
  char text[768];
  std::snprintf(text, sizeof text,
                "the run stopped at step %" PetscInt_FMT " (t = %.6e s), short of its end time %.6e s (%.3g %% of it), because PETSc's "
                "-ts_max_steps %" PetscInt_FMT " ended the time stepping%s. Remove -ts_max_steps: the run's length is -end_time (give "
                "an earlier -end_time to end sooner, or -end_step N to stop after step N on purpose). What was written is kept "
                "(history.csv up to step %" PetscInt_FMT ")",
                step, t, end, 100.0 * t / end, max_steps, output_.checkpoint.restart.empty() ? "" : " (a checkpoint's stored options count)",
                step);
  *message = text;
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::Advance(PetscInt steps)
{
  PetscInt step;

  PetscFunctionBegin;
  PetscCall(TSGetStepNumber(ts_, &step));
  PetscCall(TSSetMaxSteps(ts_, step + steps));
  PetscCall(TSSetMaxTime(ts_, PETSC_MAX_REAL));
  PetscCall(PetscLogStagePush(stage_step_));
  PetscCall(TSSolve(ts_, X_));
  PetscCall(PetscLogStagePop());
  PetscCheck(!stopped_on_error_, comm_, PETSC_ERR_NOT_CONVERGED, "%s", stop_reason_.c_str());
  PetscFunctionReturn(0);
}

// The driver at D = 2 and 3, chosen once from the scene (main.cpp); every file of
// the driver instantiates the members it defines (the others one by one).
template class SimulationD<2>;
template class SimulationD<3>;

} // namespace bapd
