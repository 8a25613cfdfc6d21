#pragma once
// The applied stretch over time (-load_schedule): a piecewise-linear lambda(t).
#include <vector>

namespace bapd {

// Piecewise-linear applied stretch lambda(t) through the knots (time[k], stretch[k]);
// ramps and holds are just knots. Before the first knot lambda = stretch[0], after the
// last one it stays at the last value. No knots: lambda = 1 throughout.
struct Schedule {
  std::vector<double> time, stretch;
  double              stretch_at(double t) const;
  double              rate_at(double t) const; // d lambda / dt (right derivative)
  double              end_time() const { return time.empty() ? 0.0 : time.back(); }
};

} // namespace bapd
