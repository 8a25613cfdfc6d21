#pragma once
// The time-stepping section's records that the operators read: the stable step's
// re-estimate (-time_step_*, time_step_control.hpp) and the damping route
// (-relaxation, relaxation.hpp). Read and checked with the scene (scene_time_stepping.cpp).
#include <petscsys.h>

#include <string>

namespace bapd {

// -time_step_reestimate, -time_step_reestimate_iterations, ..._stretch, -time_step_band.
struct TimeStepOptions {
  PetscInt interval   = 50;   // steps between re-estimates (0: the step at rest all run long)
  PetscInt iterations = 1;    // fewest power iterations per re-estimate (one force evaluation each)
  PetscInt max_iterations = 8; // most, while lambda still moves by more than tolerance per iteration
  double   tolerance  = 0.005; // measured on the Jm = 8 plate: 0.01 stalls 30 % below lambda_max (docs/stability.md section 8)
  double   band       = 0.05; // dead band of the stiffness step [-]
  double   floor      = -1;   // the stiffness step is at least this x base (-1: 0.1, or 0.5 with failure)
  double   stretch    = 0.05; // ...and whenever the applied stretch moved by this much since the last one
  double   shift      = 0.45; // the power iteration runs on A - shift lambda I: faster convergence to lambda_max
  PetscInt backoff    = 4;    // while the estimates find nothing that moves the step, interval and stretch grow up to this x
  bool     krylov     = true; // Rayleigh-Ritz on the Krylov space of the iterations (Arnoldi) instead of the last power iterate
  bool     monitor    = false; // a line per re-estimate (measurements, docs/stability.md section 8)
  bool     allow_unstable = false; // -time_step_allow_unstable: a -time_step or -ts_dt above the stable step is run (it blows up), not refused
  PetscInt reference  = 0;     // measurements: every 25 steps, also a converged lambda_max of the same state (this many evaluations, not counted)
  bool     indicator  = false; // the search only when the points' stiffening indicator rose (StiffeningIndicator): measured, not the default
  bool     bonds      = false; // ...or when the kernel's stiffest bond stiffened (BondIndicator)
  // The indicator's growth since the last search that calls the next one (Reestimate).
  // 1.5: lambda_max grew about as psi^0.4 on the Jm = 8 plate (psi 5.9 -> 15.8 while
  // lambda 1.29 -> 1.9 x), so about 18 % in lambda; (1 + band)^2 searched on every ramp
  // estimate (45 evaluations, the mode found 40 steps later).
  double   growth     = 1.5;
  PetscInt tip        = 4;     // Krylov steps of the crack-tip search after a step that broke bonds (0: off)
  std::string estimate     = "krylov"; // -time_step_estimate as given: krylov | power (startup_krylov says which)
  bool     startup_krylov = true; // the set-up's estimate by the Krylov search (else 60 power iterations)
};


enum class RelaxationKind { none, adaptive };

} // namespace bapd
