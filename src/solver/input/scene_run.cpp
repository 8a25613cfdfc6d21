// The run section: the solver (-solver), who splits the body over the ranks
// (-partition_type), the set-up's memory report and the static solver's load stepping
// (-static_*). One block of three tables: the choices as given (checked in CheckRun),
// the set-up report, the static solver's options.
#include <string>

#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/input/scene_input.hpp"

namespace bapd {

namespace {

// The solver and partition as given (CheckRun parses them), and the set-up's report.
const OptionTable<RunSection, SceneInput> kRunOptions = {
    {"-solver",
     "How the run reaches its states: dynamic (explicit dynamics, PETSc TS) or static (static states by Newton, "
     "PETSc SNES, load steps along -load_schedule)",
     GivenText<SceneInput>{&SceneInput::solver}},
    {"-partition_type",
     "Who splits the body over the ranks: metis (rank 0 builds the whole body and bond graph, METIS splits it) or "
     "ptscotch (PT-Scotch on every rank; the families are built in slabs, one a rank, and no rank holds the whole "
     "bond graph; -force_patch_correction is still built on rank 0)",
     GivenText<SceneInput>{&SceneInput::partition_type}},
    {"-log_setup_memory",
     "Print the set-up's wall time and peak memory (VmHWM) of the largest rank, the mean rank and rank 0 once the "
     "body is distributed",
     &RunSection::log_setup_memory},
};

const OptionTable<StaticOptions> kStaticSolverOptions = {
    {"-static_stretch_step", "Static solver: the first load step [stretch], > 0", &StaticOptions::stretch_step},
    {"-static_stretch_step_max", "Static solver: the largest load step [stretch], > 0", &StaticOptions::stretch_step_max},
    {"-static_stretch_step_min", "Static solver: a load step cut back below this ends the run with an error [stretch], > 0",
     &StaticOptions::stretch_step_min},
    {"-static_step_growth", "Static solver: the load step grows by this factor after a fast step [-], >= 1", &StaticOptions::growth},
    {"-static_fast_iterations", "Static solver: a load step that converged in at most this many Newton iterations is fast [-]",
     &StaticOptions::fast_iterations},
    {"-static_secant_predictor",
     "Static solver: predict a load step by the secant through the last two states (no solve); false: one tangent "
     "solve with the grips' increment every step",
     &StaticOptions::secant_predictor},
    {"-static_residual_tolerance",
     "Static solver: Newton ends once the free points' force norm is this fraction of the grips' reaction norm [-], > 0",
     &StaticOptions::residual_tolerance},
    {"-static_onset_tolerance",
     "Static solver with failure: the load step in which the first bonds break is cut back until it is at most this "
     "fraction of the strain (lambda - 1) wide [-], > 0",
     &StaticOptions::onset_tolerance},
};

} // namespace

PetscErrorCode ReadRun(MPI_Comm comm, RunSection *run, SceneInput *in)
{
  PetscFunctionBeginUser;
  PetscCall(ReadOptionBlock(comm, nullptr, "Solver", [&](OptionReader &r) -> PetscErrorCode {
    PetscCall(ReadOptionRows(r, kRunOptions, run, in));
    return ReadOptionRows(r, kStaticSolverOptions, &run->static_options);
  }));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckRun(MPI_Comm comm, const SceneInput &in, Scene *scene)
{
  PetscFunctionBeginUser;
  SceneCheck(in.solver == "dynamic" || in.solver == "static", comm,
             "-solver '%s' is not a solver: choose dynamic (explicit dynamics, the default) or static (static states by Newton)",
             in.solver.c_str());
  scene->run.solver = in.solver == "static" ? SolverKind::static_newton : SolverKind::dynamic;
  SceneCheck(in.partition_type == "metis" || in.partition_type == "ptscotch", comm,
             "-partition_type '%s' is not a partitioner: choose metis (the default) or ptscotch (in parallel)", in.partition_type.c_str());
  scene->run.partition_type = in.partition_type == "ptscotch" ? PartitionType::ptscotch : PartitionType::metis;
  const StaticOptions &s = scene->run.static_options;
  SceneCheck(s.stretch_step > 0 && s.stretch_step_max > 0 && s.stretch_step_min > 0 && s.stretch_step_min <= s.stretch_step &&
                 s.stretch_step <= s.stretch_step_max,
             comm,
             "-static_stretch_step %g, -static_stretch_step_min %g, -static_stretch_step_max %g: give 0 < min <= step <= max "
             "(defaults 1e-4, 0.25, 1)",
             s.stretch_step, s.stretch_step_min, s.stretch_step_max);
  SceneCheck(s.growth >= 1, comm, "-static_step_growth %g: give a factor >= 1 (1: the load step never grows; default 1.5)", s.growth);
  SceneCheck(s.fast_iterations >= 0, comm, "-static_fast_iterations %" PetscInt_FMT ": give N >= 0 (default 4)", s.fast_iterations);
  SceneCheck(s.residual_tolerance > 0 && s.residual_tolerance < 1, comm,
             "-static_residual_tolerance %g: give a small positive fraction such as 1e-10", s.residual_tolerance);
  SceneCheck(s.onset_tolerance > 0 && s.onset_tolerance < 1, comm,
             "-static_onset_tolerance %g: give a small positive fraction such as 1e-3 (the default)", s.onset_tolerance);
  PetscFunctionReturn(0);
}

} // namespace bapd
