// Time-step control: its options (-time_step_*), read and checked once at set-up.
#include "bapd/solver/operators/time_step_control.hpp"

#include <string>

#include "bapd/solver/input/options_reader.hpp"

namespace bapd {

PetscErrorCode TimeStepOptionsFromOptions(MPI_Comm comm, TimeStepOptions *options)
{
  PetscFunctionBeginUser;
  // Read as the scene's options are (options_reader.hpp): named in -help, known to the
  // typo check, a malformed value refused naming its option.
  PetscCall(ReadOptionBlock(comm, nullptr, "Time step that follows the material", [&](OptionReader &r) -> PetscErrorCode {
    PetscCall(r.Int("-time_step_reestimate",
                    "Time steps between re-estimates of the stable step from the current state [-] (0: the step at rest for the whole "
                    "run, as in the paper)",
                    &options->interval));
    PetscCall(r.Int("-time_step_reestimate_iterations", "Fewest power iterations per re-estimate [-], >= 1 (one force evaluation each)",
                    &options->iterations));
    PetscCall(r.Real("-time_step_band",
                     "Dead band of the re-estimated step [-], in [0, 0.5): it shrinks or grows back only when the stable step moved by "
                     "more than this fraction",
                     &options->band));
    PetscCall(r.Int("-time_step_reestimate_max_iterations", "Most power iterations per re-estimate [-] while the estimate still moves",
                    &options->max_iterations));
    PetscCall(r.Real("-time_step_reestimate_tolerance", "A re-estimate stops once lambda_max moves by less than this fraction per iteration [-]",
                     &options->tolerance));
    PetscCall(r.Real("-time_step_floor",
                     "The re-estimated step is at least this fraction of the base step [-], in (0, 1] (default -1: 0.1, or 0.5 with "
                     "failure, where the travel limit handles the bonds about to snap)",
                     &options->floor));
    PetscCall(r.Real("-time_step_reestimate_stretch", "Re-estimate also whenever the applied stretch moved by this much since the last one [-] (fast ramps)",
                     &options->stretch));
    PetscCall(r.Real("-time_step_shift", "Shift of the re-estimate's power iteration, a fraction of the last lambda_max [-], in [0, 0.5]",
                     &options->shift));
    PetscCall(r.Int("-time_step_reestimate_backoff",
                    "While re-estimates find nothing that would move the step, the steps and the stretch increment between them double, "
                    "up to this factor [-], >= 1 (1: every -time_step_reestimate steps and -time_step_reestimate_stretch, always)",
                    &options->backoff));
    PetscCall(r.Bool("-time_step_krylov",
                     "Each re-estimate takes the largest Rayleigh quotient over the Krylov space its force evaluations span (Arnoldi, "
                     "Rayleigh-Ritz) instead of the last power iterate's: the same evaluations, a sharper estimate (0: the power iteration)",
                     &options->krylov));
    PetscCall(r.Bool("-time_step_reestimate_indicator",
                     "Measurements (off by default): while the step is shortened, the re-estimate searches (at least 4 Krylov steps, the "
                     "start vector mixed into the warm start) only when the points' stiffening indicator (their largest Gent factor "
                     "squared x I1bar / 3) grew by 1.5 x since the last search, instead of whenever the load moves (0: the latter)",
                     &options->indicator));
    PetscCall(r.Bool("-time_step_reestimate_bonds",
                     "Measurements (off by default): as -time_step_reestimate_indicator, with the Gent factor of the stiffest bond "
                     "the force kernel saw in the dynamics' own evaluation (no extra bond loop) as the indicator; a search runs all "
                     "its Krylov steps, an estimate without one stops after a first step within half the dead band, and from a Gent "
                     "factor of 4 every shortened estimate searches as without an indicator",
                     &options->bonds));
    PetscCall(r.Real("-time_step_reestimate_growth",
                     "With -time_step_reestimate_indicator or _bonds: the indicator's growth since the last search that calls the next "
                     "one [-], > 1 (default 1.5)",
                     &options->growth));
    PetscCall(r.Bool("-time_step_allow_unstable",
                     "Run a -time_step (or -ts_dt) more than 5 % above the estimated stable step instead of refusing it: for studies "
                     "of the blow-up and its diagnosis (the run is expected to diverge)",
                     &options->allow_unstable));
    PetscCall(r.Bool("-time_step_monitor", "Print a line per re-estimate of the stable step (step, lambda_max, stable step, step in use)",
                     &options->monitor));
    PetscCall(r.Int("-time_step_crack_tip",
                    "With failure: after a step that broke bonds, this many Krylov steps search the stiffest mode around the broken "
                    "bonds (a partly broken family at a crack tip is stiffer than the body), which shortens the step at once when "
                    "it is stiffer than the estimate in use [-], 0 to 15 (default 4; 0: off, the paper's fixed step)",
                    &options->tip));
    std::string estimate = options->startup_krylov ? "krylov" : "power";
    PetscCall(r.String("-time_step_estimate",
                       "The stable step at rest: krylov (the default: the Krylov search until its largest Ritz value moves by less "
                       "than 0.1 % a step twice in a row, at most 60 force evaluations) | power (60 power iterations: the estimate of earlier "
                       "versions, bit for bit)",
                       &estimate));
    PetscCheck(estimate == "krylov" || estimate == "power", comm, PETSC_ERR_USER,
               "-time_step_estimate '%s' is not an estimate: choose krylov (the default) or power (60 power iterations, as earlier "
               "versions)",
               estimate.c_str());
    options->startup_krylov = estimate == "krylov";
    PetscCall(r.Int("-time_step_monitor_reference",
                    "Measurements: every 25 steps, also print a converged lambda_max of the same state by this many force evaluations "
                    "(restarted Krylov; not counted in the cost, the run's steps unchanged) next to the estimate in use [-] (0: off)",
                    &options->reference));
    return 0;
  }));
  PetscCheck(options->interval >= 0, comm, PETSC_ERR_USER,
             "-time_step_reestimate %" PetscInt_FMT ": give the number of steps between re-estimates (>= 1), or 0 to keep the step at rest",
             options->interval);
  PetscCheck(options->iterations >= 1, comm, PETSC_ERR_USER,
             "-time_step_reestimate_iterations %" PetscInt_FMT ": give at least 1 power iteration per re-estimate (default 1)",
             options->iterations);
  PetscCheck(options->reference >= 0, comm, PETSC_ERR_USER,
             "-time_step_monitor_reference %" PetscInt_FMT ": give the force evaluations of the reference estimate (e.g. 60), or 0 for none",
             options->reference);
  PetscCheck(options->floor == -1 || (options->floor > 0 && options->floor <= 1), comm, PETSC_ERR_USER,
             "-time_step_floor %g: give a fraction of the base step in (0, 1], or -1 for the solver's choice", options->floor);
  PetscCheck(options->shift >= 0 && options->shift <= 0.5, comm, PETSC_ERR_USER,
             "-time_step_shift %g: give a fraction of lambda_max in [0, 0.5] (default 0.45; above 0.5 the low end of the spectrum would dominate)",
             options->shift);
  PetscCheck(options->max_iterations >= 1 && options->max_iterations <= 15 && options->tolerance >= 0, comm, PETSC_ERR_USER,
             "-time_step_reestimate_max_iterations %" PetscInt_FMT " / -time_step_reestimate_tolerance %g: give 1 to 15 iterations and a tolerance >= 0 (defaults 8, 0.005)",
             options->max_iterations, options->tolerance);
  PetscCheck(options->stretch > 0, comm, PETSC_ERR_USER,
             "-time_step_reestimate_stretch %g: give a stretch increment > 0 (default 0.05)", options->stretch);
  PetscCheck(options->backoff >= 1, comm, PETSC_ERR_USER,
             "-time_step_reestimate_backoff %" PetscInt_FMT ": give a factor >= 1 (default 4; 1 keeps the interval and stretch increment fixed)",
             options->backoff);
  PetscCheck(options->tip >= 0 && options->tip <= 15, comm, PETSC_ERR_USER,
             "-time_step_crack_tip %" PetscInt_FMT ": give 0 to 15 Krylov steps (default 4; 0 turns the crack-tip search off)", options->tip);
  PetscCheck(options->growth > 1, comm, PETSC_ERR_USER, "-time_step_reestimate_growth %g: give a factor > 1 (default 1.5)", options->growth);
  PetscCheck(!(options->indicator && options->bonds), comm, PETSC_ERR_USER,
             "-time_step_reestimate_indicator and -time_step_reestimate_bonds: give one of the two indicators");
  PetscCheck(options->band >= 0 && options->band < 0.5, comm, PETSC_ERR_USER,
             "-time_step_band %g: give a fraction in [0, 0.5) (default 0.05)", options->band);
  PetscFunctionReturn(0);
}

} // namespace bapd
