// The stretch schedule lambda(t): piecewise linear through its knots
// (scene_schedule.hpp). Read and checked with the loading (scene_loading.cpp).
#include "bapd/solver/input/scene_schedule.hpp"

#include <algorithm>
#include <cstddef>

namespace bapd {

double Schedule::stretch_at(double t) const
{
  if (time.empty()) return 1.0;
  if (t <= time.front()) return stretch.front();
  if (t >= time.back()) return stretch.back();
  // time[k - 1] <= t < time[k]
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(time.begin(), time.end(), t) - time.begin());
  const double      a = (t - time[k - 1]) / (time[k] - time[k - 1]);
  return stretch[k - 1] + a * (stretch[k] - stretch[k - 1]);
}

double Schedule::rate_at(double t) const
{
  if (time.size() < 2 || t < time.front() || t >= time.back()) return 0.0;
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(time.begin(), time.end(), t) - time.begin());
  return (stretch[k] - stretch[k - 1]) / (time[k] - time[k - 1]);
}

} // namespace bapd
