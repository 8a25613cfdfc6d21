// The time-stepping section: the step (-time_step, -time_step_safety, -time_step_travel),
// damping (-damping, -relaxation), holds (-static_tolerance), the run's end (-end_time,
// -end_step), progress lines, and the stable step's re-estimate during the run
// (-time_step_reestimate, ..., time_step_control.hpp). Each block is one option table.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/input/scene_input.hpp"

namespace bapd {

namespace {

// The step, damping, the run's end and progress: values in the Scene, whether -end_time
// was given in the SceneInput.
const OptionTable<TimeSteppingSection, SceneInput> kStepOptions = {
    {"-time_step", "Time step [s]; 0: time_step_safety x the estimated stable step", &TimeSteppingSection::step},
    {"-time_step_safety", "Fraction of the estimated stable step [-], in (0, 1]", &TimeSteppingSection::safety},
    {"-time_step_travel",
     "Largest distance a point with bonds may move in one step [dx]; the step shrinks while points move fast (snapping "
     "bonds), 0: never, -1 (default): 0.1 with failure, off without",
     &TimeSteppingSection::travel},
    {"-damping", "Mass-proportional damping coefficient [1/s], >= 0", &TimeSteppingSection::damping},
    {"-static_tolerance", "A hold of the load schedule ends once kinetic/internal energy < this [-] (0: holds run their full length)",
     &TimeSteppingSection::static_tolerance},
    {"-end_time", "End of the run [s] (default: the schedule's last time)", &TimeSteppingSection::end_time, &SceneInput::end_time_set},
    {"-end_step",
     "Stop after this time step [-] (a step number: a restart goes on counting), before -end_time, on purpose: a run in "
     "parts, a test, a benchmark (-1: run to -end_time)",
     &TimeSteppingSection::end_step},
    {"-progress_interval", "Time steps between progress lines [-] (0: every end time / 20 of simulated time)", &TimeSteppingSection::progress_interval},
    {"-progress_wall_interval", "Also a progress line once this much wall time has passed since the last one [s] (0: off)",
     &TimeSteppingSection::progress_wall_interval},
};

const OptionTable<SceneInput> kRelaxationOptions = {
    {"-relaxation",
     "Damping route to static states: none (the -damping coefficient) or adaptive (adaptive dynamic relaxation: c = 2 "
     "omega_min estimated every step, at least -damping)",
     &SceneInput::relaxation},
};

// The re-estimate of the stable step during the run (time_step_control.hpp).
const OptionTable<TimeStepOptions> kReestimateOptions = {
    {"-time_step_reestimate",
     "Time steps between re-estimates of the stable step from the current state [-] (0: the step at rest for the whole "
     "run, as in the paper)",
     &TimeStepOptions::interval},
    {"-time_step_reestimate_iterations",
     "Fewest power iterations per re-estimate [-], >= 1 (one force evaluation each)",
     &TimeStepOptions::iterations},
    {"-time_step_band",
     "Dead band of the re-estimated step [-], in [0, 0.5): it shrinks or grows back only when the stable step moved by "
     "more than this fraction",
     &TimeStepOptions::band},
    {"-time_step_reestimate_max_iterations",
     "Most power iterations per re-estimate [-] while the estimate still moves",
     &TimeStepOptions::max_iterations},
    {"-time_step_reestimate_tolerance",
     "A re-estimate stops once lambda_max moves by less than this fraction per iteration [-]",
     &TimeStepOptions::tolerance},
    {"-time_step_floor",
     "The re-estimated step is at least this fraction of the base step [-], in (0, 1] (default -1: 0.1, or 0.5 with "
     "failure, where the travel limit handles the bonds about to snap)",
     &TimeStepOptions::floor},
    {"-time_step_reestimate_stretch",
     "Re-estimate also whenever the applied stretch moved by this much since the last one [-] (fast ramps)",
     &TimeStepOptions::stretch},
    {"-time_step_shift",
     "Shift of the re-estimate's power iteration, a fraction of the last lambda_max [-], in [0, 0.5]",
     &TimeStepOptions::shift},
    {"-time_step_reestimate_backoff",
     "While re-estimates find nothing that would move the step, the steps and the stretch increment between them double, "
     "up to this factor [-], >= 1 (1: every -time_step_reestimate steps and -time_step_reestimate_stretch, always)",
     &TimeStepOptions::backoff},
    {"-time_step_krylov",
     "Each re-estimate takes the largest Rayleigh quotient over the Krylov space its force evaluations span (Arnoldi, "
     "Rayleigh-Ritz) instead of the last power iterate's: the same evaluations, a sharper estimate (0: the power iteration)",
     &TimeStepOptions::krylov},
    {"-time_step_reestimate_indicator",
     "Measurements (off by default): while the step is shortened, the re-estimate searches (at least 4 Krylov steps, the "
     "start vector mixed into the warm start) only when the points' stiffening indicator (their largest Gent factor "
     "squared x I1bar / 3) grew by 1.5 x since the last search, instead of whenever the load moves (0: the latter)",
     &TimeStepOptions::indicator},
    {"-time_step_reestimate_bonds",
     "Measurements (off by default): as -time_step_reestimate_indicator, with the Gent factor of the stiffest bond "
     "the force kernel saw in the dynamics' own evaluation (no extra bond loop) as the indicator; a search runs all "
     "its Krylov steps, an estimate without one stops after a first step within half the dead band, and from a Gent "
     "factor of 4 every shortened estimate searches as without an indicator",
     &TimeStepOptions::bonds},
    {"-time_step_reestimate_growth",
     "With -time_step_reestimate_indicator or _bonds: the indicator's growth since the last search that calls the next "
     "one [-], > 1 (default 1.5)",
     &TimeStepOptions::growth},
    {"-time_step_allow_unstable",
     "Run a -time_step (or -ts_dt) more than 5 % above the estimated stable step instead of refusing it: for studies "
     "of the blow-up and its diagnosis (the run is expected to diverge)",
     &TimeStepOptions::allow_unstable},
    {"-time_step_monitor",
     "Print a line per re-estimate of the stable step (step, lambda_max, stable step, step in use)",
     &TimeStepOptions::monitor},
    {"-time_step_crack_tip",
     "With failure: after a step that broke bonds, this many Krylov steps search the stiffest mode around the broken "
     "bonds (a partly broken family at a crack tip is stiffer than the body), which shortens the step at once when "
     "it is stiffer than the estimate in use [-], 0 to 15 (default 4; 0: off, the paper's fixed step)",
     &TimeStepOptions::tip},
    {"-time_step_estimate",
     "The stable step at rest: krylov (the default: the Krylov search until its largest Ritz value moves by less "
     "than 0.1 % a step twice in a row, at most 60 force evaluations) | power (60 power iterations: the estimate of earlier "
     "versions, bit for bit)",
     &TimeStepOptions::estimate},
    {"-time_step_monitor_reference",
     "Measurements: every 25 steps, also print a converged lambda_max of the same state by this many force evaluations "
     "(restarted Krylov; not counted in the cost, the run's steps unchanged) next to the estimate in use [-] (0: off)",
     &TimeStepOptions::reference},
};

// The re-estimate's options; -time_step_estimate's word into startup_krylov.
PetscErrorCode CheckReestimate(MPI_Comm comm, TimeStepOptions *reestimate)
{
  const TimeStepOptions &options = *reestimate;
  PetscFunctionBeginUser;
  PetscCheck(options.estimate == "krylov" || options.estimate == "power", comm, PETSC_ERR_USER,
             "-time_step_estimate '%s' is not an estimate: choose krylov (the default) or power (60 power iterations, as earlier "
             "versions)",
             options.estimate.c_str());
  reestimate->startup_krylov = options.estimate == "krylov";
  PetscCheck(options.interval >= 0, comm, PETSC_ERR_USER,
             "-time_step_reestimate %" PetscInt_FMT ": give the number of steps between re-estimates (>= 1), or 0 to keep the step at rest",
             options.interval);
  PetscCheck(options.iterations >= 1, comm, PETSC_ERR_USER,
             "-time_step_reestimate_iterations %" PetscInt_FMT ": give at least 1 power iteration per re-estimate (default 1)",
             options.iterations);
  PetscCheck(options.reference >= 0, comm, PETSC_ERR_USER,
             "-time_step_monitor_reference %" PetscInt_FMT ": give the force evaluations of the reference estimate (e.g. 60), or 0 for none",
             options.reference);
  PetscCheck(options.floor == -1 || (options.floor > 0 && options.floor <= 1), comm, PETSC_ERR_USER,
             "-time_step_floor %g: give a fraction of the base step in (0, 1], or -1 for the solver's choice", options.floor);
  PetscCheck(options.shift >= 0 && options.shift <= 0.5, comm, PETSC_ERR_USER,
             "-time_step_shift %g: give a fraction of lambda_max in [0, 0.5] (default 0.45; above 0.5 the low end of the spectrum would dominate)",
             options.shift);
  PetscCheck(options.max_iterations >= 1 && options.max_iterations <= 15 && options.tolerance >= 0, comm, PETSC_ERR_USER,
             "-time_step_reestimate_max_iterations %" PetscInt_FMT " / -time_step_reestimate_tolerance %g: give 1 to 15 iterations and a tolerance >= 0 (defaults 8, 0.005)",
             options.max_iterations, options.tolerance);
  PetscCheck(options.stretch > 0, comm, PETSC_ERR_USER,
             "-time_step_reestimate_stretch %g: give a stretch increment > 0 (default 0.05)", options.stretch);
  PetscCheck(options.backoff >= 1, comm, PETSC_ERR_USER,
             "-time_step_reestimate_backoff %" PetscInt_FMT ": give a factor >= 1 (default 4; 1 keeps the interval and stretch increment fixed)",
             options.backoff);
  PetscCheck(options.tip >= 0 && options.tip <= 15, comm, PETSC_ERR_USER,
             "-time_step_crack_tip %" PetscInt_FMT ": give 0 to 15 Krylov steps (default 4; 0 turns the crack-tip search off)", options.tip);
  PetscCheck(options.growth > 1, comm, PETSC_ERR_USER, "-time_step_reestimate_growth %g: give a factor > 1 (default 1.5)", options.growth);
  PetscCheck(!(options.indicator && options.bonds), comm, PETSC_ERR_USER,
             "-time_step_reestimate_indicator and -time_step_reestimate_bonds: give one of the two indicators");
  PetscCheck(options.band >= 0 && options.band < 0.5, comm, PETSC_ERR_USER,
             "-time_step_band %g: give a fraction in [0, 0.5) (default 0.05)", options.band);
  PetscFunctionReturn(0);
}

// Refuses an end time whose time steps no run can count (PetscInt) or finish. The
// step is not known before the body is built (power iteration, docs/method.md section 5),
// so the count is bounded from below with a generous upper bound on the step: the
// stable step of the explicit scheme is about dx over the fastest wave speed, and the
// shear wave speed sqrt(mu / rho) is the slowest (measured: 1.1 dx / sqrt(mu / rho)
// on the tiny test scene); three times that bounds it.
PetscErrorCode CheckStepCount(MPI_Comm comm, const Scene &scene, bool end_time_set)
{
  PetscFunctionBeginUser;
  const double      max_steps  = static_cast<double>(std::numeric_limits<PetscInt>::max());
  const double      shear_wave = std::sqrt(scene.material.parameters.mu / scene.material.density);
  const bool        given      = scene.time_stepping.step > 0;
  const double      step_bound = given ? scene.time_stepping.step : 3.0 * scene.time_stepping.safety * scene.body.dx() / shear_wave;
  const double      steps      = scene.time_stepping.end_time / step_bound;
  const std::string how        = given ? Format("-time_step %g s", scene.time_stepping.step)
                                       : Format("the step, at most about %g s here (3 x %g x dx / sqrt(mu / rho))", step_bound,
                                                scene.time_stepping.safety);
  const double      longest    = max_steps * step_bound;
  const std::string head       = end_time_set ? Format("-end_time %g s", scene.time_stepping.end_time)
                                              : Format("-load_schedule ends at %g s, which", scene.time_stepping.end_time);
  SceneCheck(steps <= max_steps, comm,
             "%s needs %s%.3g time steps with %s, more than a run can count (%.0f): end the run by %.3g s, e.g. -end_time %g",
             head.c_str(), given ? "" : "at least ", steps, how.c_str(), max_steps, longest, std::min(1.0, 0.5 * longest));
  PetscFunctionReturn(0);
}

} // namespace

std::string TimeSteppingText(const Scene &s)
{
  std::string text;
  if (s.time_stepping.step > 0) text += Format("  time      step %g s", s.time_stepping.step);
  else text += Format("  time      step %g x the stable step", s.time_stepping.safety);
  if (s.time_stepping.travel > 0) text += Format(" (shorter while a point with bonds would move > %g dx a step)", s.time_stepping.travel);
  else if (s.time_stepping.travel < 0 && s.failure.enabled) text += " (shorter while a point with bonds would move > 0.1 dx a step)";
  text += Format(", damping %g 1/s, end %g s", s.time_stepping.damping, s.time_stepping.end_time);
  if (s.time_stepping.end_step >= 0) text += Format(" or after step %ld (-end_step), whichever comes first", (long)s.time_stepping.end_step);
  text += "\n";
  if (s.time_stepping.static_tolerance > 0)
    text += Format("  static    a hold ends once kinetic energy < %g x internal energy (checked every %ld steps, at the -output_interval rows)\n", s.time_stepping.static_tolerance,
                   (long)s.output.interval);
  return text;
}

PetscErrorCode ReadTimeStepping(MPI_Comm comm, TimeSteppingSection *time_stepping, SceneInput *in)
{
  PetscFunctionBeginUser;
  PetscCall(ReadOptionTable(comm, "Time stepping (explicit dynamics)", kStepOptions, time_stepping, in));
  PetscCall(ReadOptionTable(comm, "Static states (relaxation)", kRelaxationOptions, in));
  PetscCall(ReadOptionTable(comm, "Time step that follows the material", kReestimateOptions, &time_stepping->reestimate));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckTimeStepping(MPI_Comm comm, const SceneInput &in, Scene *scene)
{
  PetscFunctionBeginUser;
  SceneCheck(scene->time_stepping.step >= 0, comm,
             "-time_step %g: the time step must be > 0 s, or 0 for the automatic choice (safety x stable step)", scene->time_stepping.step);
  SceneCheck(scene->time_stepping.safety > 0, comm,
             "-time_step_safety %g must be > 0: it is the fraction of the estimated stable step that is taken (default 0.8)",
             scene->time_stepping.safety);
  if (scene->time_stepping.safety > 1)
    PetscCall(Warn(comm,
                   Format("-time_step_safety %g is above 1: the time step exceeds the estimated stable step and the explicit scheme "
                          "may blow up; use a value in (0, 1] (default 0.8)",
                          scene->time_stepping.safety),
                   true));
  SceneCheck(scene->time_stepping.travel >= 0 || scene->time_stepping.travel == -1, comm,
             "-time_step_travel %g must be >= 0: it is the largest distance, in dx, that a point with bonds may move in one step (0: off; -1, the default: 0.1 with failure, off without)",
             scene->time_stepping.travel);
  SceneCheck(scene->time_stepping.damping >= 0, comm, "-damping %g: the damping coefficient must be >= 0 1/s (0: undamped)", scene->time_stepping.damping);
  const std::string relaxation = Lower(in.relaxation);
  SceneCheck(relaxation == "none" || relaxation == "adaptive", comm,
             "-relaxation '%s' is not a relaxation route: choose none (fixed -damping) or adaptive (adaptive dynamic relaxation)",
             in.relaxation.c_str());
  scene->time_stepping.relaxation = relaxation == "adaptive" ? RelaxationKind::adaptive : RelaxationKind::none;
  SceneCheck(scene->time_stepping.static_tolerance >= 0 && scene->time_stepping.static_tolerance < 1, comm,
             "-static_tolerance %g: use a small positive ratio such as 1e-6 (0: holds run their full length)", scene->time_stepping.static_tolerance);
  SceneCheck(scene->time_stepping.progress_interval >= 0, comm,
             "-progress_interval %" PetscInt_FMT ": give N >= 1 time steps between progress lines, or 0 for about 20 lines a run",
             scene->time_stepping.progress_interval);
  SceneCheck(scene->time_stepping.progress_wall_interval >= 0, comm,
             "-progress_wall_interval %g: give the wall time between progress lines in seconds, > 0 (default 10), or 0 for lines by "
             "simulated time (or -progress_interval) only",
             scene->time_stepping.progress_wall_interval);
  SceneCheck(scene->time_stepping.end_step >= -1, comm,
             "-end_step %" PetscInt_FMT ": give the step number after which the run stops (>= 0), or -1 to run to -end_time",
             scene->time_stepping.end_step);
  const double schedule_end = scene->loading.schedule.end_time();
  if (in.end_time_set) {
    SceneCheck(scene->time_stepping.end_time > 0, comm, "-end_time %g: the run must end after t = 0 s", scene->time_stepping.end_time);
    if (scene->time_stepping.end_time < schedule_end)
      PetscCall(Warn(comm, Format("-end_time %g s stops the run before the end of -load_schedule (%g s)", scene->time_stepping.end_time, schedule_end)));
  } else {
    SceneCheck(schedule_end > 0, comm,
               "-end_time is required when -load_schedule does not end after t = 0: give the run's end in s, e.g. -end_time 1%s",
               (MisspeltHint("-end_time") + MisspeltHint("-load_schedule")).c_str());
    scene->time_stepping.end_time = schedule_end;
  }
  PetscCall(CheckStepCount(comm, *scene, in.end_time_set));
  PetscCall(CheckReestimate(comm, &scene->time_stepping.reestimate));
  // The points' indicator forms F~ and the plane-stress I1bar of a 2D point (the dynamics'
  // re-estimate only: the static solver takes no time step).
  SceneCheck(scene->body.dimension == 2 || !scene->time_stepping.reestimate.indicator || scene->run.solver == SolverKind::static_newton, comm,
             "-time_step_reestimate_indicator is a 2D measurement (the points' plane-stress I1bar): leave it out for a 3D body, or use "
             "-time_step_reestimate_bonds");
  PetscFunctionReturn(0);
}

} // namespace bapd
