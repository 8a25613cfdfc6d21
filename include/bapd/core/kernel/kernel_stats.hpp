#pragma once
// What a force evaluation reports (ba_force.hpp, for every D): how many bonds it
// handed to the model, how many it skipped for want of a usable K, and the bonds whose
// model failed (StressStatus), counted and listed in loop order.
#include <cstddef>
#include <limits>

#include "bapd/core/materials/stress_status.hpp"

namespace bapd {

// A bond whose model returned something other than StressStatus::ok.
struct FailedBond {
  std::size_t  point;    // local index of i
  std::size_t  position; // q: the bond is the q-th member of i's family
  StressStatus status;
};

struct KernelStats {
  static constexpr std::size_t none = std::numeric_limits<std::size_t>::max();

  std::size_t evaluated      = 0; // intact bonds with a usable K handed to the model
  std::size_t unusable       = 0; // intact bonds skipped because K is not usable (t = 0)
  std::size_t chain_limit    = 0; // model failures (those bonds carry t = 0 this step)
  std::size_t inverted       = 0;
  std::size_t no_convergence = 0;
  // The largest tr C = tr(F^T F) over the bonds handed to the model (in 2D plus the
  // out-of-plane C33 of the bond's warm start, 1 without one): 3 at rest. The time
  // step's stiffening trigger reads it from the dynamics' own evaluation (a maximum:
  // the same over any split of the points; time_step_control.hpp).
  double largest_trC = 0.0;
  // The first failed bond in loop order (lowest local point, then family position).
  std::size_t  first_point    = none;
  std::size_t  first_position = none;
  StressStatus first_status   = StressStatus::ok;

  std::size_t failed() const { return chain_limit + inverted + no_convergence; }
  bool        ok() const { return failed() == 0; }
  void        record(std::size_t i, std::size_t q, StressStatus s)
  {
    if (s == StressStatus::chain_limit) ++chain_limit;
    else if (s == StressStatus::inverted) ++inverted;
    else ++no_convergence;
    if (first_point == none) {
      first_point    = i;
      first_position = q;
      first_status   = s;
    }
  }
};

} // namespace bapd
