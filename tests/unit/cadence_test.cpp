// Output by simulated time (cadence.hpp): the count promised is the count written
// whatever the step does, and a restart continues as the uninterrupted run.
#include <gtest/gtest.h>

#include <vector>

#include "bapd/solver/io/cadence.hpp"

namespace {

// Steps of varying size (a shortened stretch in the middle) up to end_time; the
// times at which the cadence was due.
std::vector<double> DueTimes(bapd::Cadence &c, double t0, double end_time, std::vector<double> *times)
{
  std::vector<double> due;
  double              t = t0;
  for (int k = 0; t < end_time; ++k) {
    const double dt = (k > 300 && k < 2300) ? 1e-5 : 2e-4; // 0.02 s of a 100x shorter step
    t += dt;
    if (times) times->push_back(t);
    if (c.Due(t)) due.push_back(t);
  }
  return due;
}

TEST(Cadence, CountFollowsSimulatedTimeNotSteps)
{
  bapd::Cadence c;
  c.Start(1.0 / 20, 0.0);
  const std::vector<double> due = DueTimes(c, 0.0, 1.0, nullptr);
  // One per 1/20 s: 20, however many steps the short stretch took (a count by steps,
  // sized from the first step, would give far more).
  EXPECT_EQ(due.size(), 20u);
  for (std::size_t k = 0; k < due.size(); ++k) {
    EXPECT_GE(due[k], (k + 1) / 20.0);
    EXPECT_LT(due[k], (k + 1) / 20.0 + 2e-4 + 1e-15);
  }
}

TEST(Cadence, RestartContinuesAsTheUninterruptedRun)
{
  bapd::Cadence       whole;
  std::vector<double> times;
  whole.Start(0.05, 0.0);
  const std::vector<double> due = DueTimes(whole, 0.0, 1.0, &times);
  // Restart at several step times (on and next to a due step): the rest is the same.
  for (std::size_t k : {std::size_t(10), std::size_t(249), std::size_t(250), std::size_t(251), std::size_t(2000), times.size() - 2}) {
    const double  t0 = times[k];
    bapd::Cadence rest;
    rest.Start(0.05, t0);
    std::vector<double> expected;
    for (double d : due)
      if (d > t0) expected.push_back(d);
    std::vector<double> got;
    for (std::size_t j = k + 1; j < times.size(); ++j)
      if (rest.Due(times[j])) got.push_back(times[j]);
    EXPECT_EQ(got, expected) << "restart after step " << k << " at t = " << t0;
  }
}

TEST(Cadence, NoPeriodIsNeverDue)
{
  bapd::Cadence c;
  c.Start(0.0, 0.0);
  EXPECT_FALSE(c.Due(1.0));
}

} // namespace
