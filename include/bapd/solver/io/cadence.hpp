#pragma once
// When to write something that comes "about 20 times a run": every `period` of
// simulated time, not every N steps counted from the step size at the start (the step
// changes during a run: fast points, a stiffening material), so that the count
// promised is the count written. Due(t) is true at the first step at or past each
// multiple of the period. After any step at time t the next due time is
// (floor(t / period) + 1) period, whether or not that step was due, so a restart at
// time t (Start(t)) continues exactly as the uninterrupted run.
#include <cmath>

namespace bapd {

class Cadence {
public:
  // Every `period` seconds of simulated time, from time t0 on (period <= 0: never due).
  void Start(double period, double t0)
  {
    period_ = period;
    next_   = period > 0 ? Next(t0) : 0;
  }
  bool Due(double t)
  {
    if (period_ <= 0 || t < next_) return false;
    next_ = Next(t);
    return true;
  }
  double period() const { return period_; }
  // The first due time after a step at t: where Due(t') turns true after a step at t
  // that was not followed by a due step (a restart reads it off the last written row).
  double Next(double t) const { return (std::floor(t / period_) + 1) * period_; }

private:
  double period_ = 0, next_ = 0;
};

} // namespace bapd
