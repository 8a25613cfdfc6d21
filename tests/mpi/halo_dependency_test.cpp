// The two-ring halo carries every value a force needs, and nothing leaks: perturbing
// one point changes the force of exactly the points whose force depends on it, on
// any rank layout.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <set>

#include "bapd/core/geometry/family.hpp"
#include "bapd/core/geometry/lattice.hpp"
#include "bapd/solver/driver/simulation.hpp"
#include "mpi/test_scenes.hpp"

using namespace bapd;

namespace {

// f_i = sum_j (t_ij - t_ji) V_j (paper eq 23). t_ij reads y over B_ij, a subset of
// family(i); t_ji reads y over B_ji = {k in family(j): |x_k - x_i| <= delta}. So in
// exact arithmetic f_i depends on y_p iff p is in family(i), or p is in family(j) for
// some j in family(i) and lies within one horizon of i (even across a notch): the
// "physical" set. The kernel forms some BA sums as (family total) - (the others), so
// at round-off f_i may also move with any member of family(j), j in family(i): the
// "reach" set, two rings of bonds, which is what the halo carries.
struct Dependence {
  std::set<int64_t> physical, reach;
};

Dependence DependentPoints(const PointCloud &cloud, const Families &fam, int64_t p)
{
  Dependence   out;
  const double d2max = fam.horizon * fam.horizon;
  auto within = [&](std::size_t a, std::size_t b) {
    const double dx = cloud.x[2 * a] - cloud.x[2 * b], dy = cloud.x[2 * a + 1] - cloud.x[2 * b + 1];
    return dx * dx + dy * dy <= d2max;
  };
  auto in_family = [&](std::size_t i, std::size_t k) {
    for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b)
      if ((std::size_t)fam.neighbour[b] == k) return true;
    return false;
  };
  for (std::size_t i = 0; i < fam.n_family; ++i) {
    if (i == (std::size_t)p) continue;
    bool physical = in_family(i, p), reach = physical;
    for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) {
      const bool member = in_family(fam.neighbour[b], p);
      physical          = physical || (member && within(i, p));
      reach             = reach || member;
    }
    if (physical) out.physical.insert((int64_t)i);
    if (reach) out.reach.insert((int64_t)i);
  }
  // The perturbed point itself: its own bonds change (if it has any).
  if (fam.size(p) > 0) out.physical.insert(p), out.reach.insert(p);
  return out;
}

std::set<int64_t> GatherIds(MPI_Comm comm, const std::vector<long long> &mine)
{
  int size, rank;
  MPI_Comm_size(comm, &size);
  MPI_Comm_rank(comm, &rank);
  int              m = (int)mine.size();
  std::vector<int> counts(size), displs(size, 0);
  MPI_Allgather(&m, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  for (int r = 1; r < size; ++r) displs[r] = displs[r - 1] + counts[r - 1];
  std::vector<long long> all(displs[size - 1] + counts[size - 1]);
  MPI_Allgatherv(mine.data(), m, MPI_LONG_LONG, all.data(), counts.data(), displs.data(), MPI_LONG_LONG, comm);
  return std::set<int64_t>(all.begin(), all.end());
}

} // namespace

TEST(HaloDependency, ExactlyTheDependencyRangeSeesAPerturbation)
{
  ASSERT_EQ(bapd_test::SetOptions(bapd_test::FreeSheetScene("halo_test_output")), 0);
  Simulation sim(PETSC_COMM_WORLD);
  ASSERT_EQ(sim.Setup(), 0);
  const Layout  &layout = sim.layout();
  const PetscInt n      = layout.n_owned;

  // A smooth, non-affine base state with finite stretches everywhere.
  std::vector<double> u(2 * n), f0(2 * n), f1(2 * n);
  for (PetscInt i = 0; i < n; ++i) {
    const double x = layout.cloud.x[2 * i] / 0.02, y = layout.cloud.x[2 * i + 1] / 0.02;
    u[2 * i]     = 0.002 * (x * y + 0.3 * std::sin(3 * y));
    u[2 * i + 1] = 0.003 * (x * x - 0.5 * y + 0.2 * std::cos(4 * x));
  }
  ASSERT_EQ(sim.ComputeForceDensity(u.data(), f0.data()), 0);

  const PointCloud global   = make_lattice(sim.scene().body.sheet);
  const Families   families = build_families(global, global.size(), sim.scene().body.horizon(), sim.scene().body.sheet.notches);
  // An interior point, one at the notch tip, one on the hole's rim, one in a corner.
  auto nearest = [&](double px, double py) {
    int64_t best = 0;
    double  bd   = 1e300;
    for (std::size_t i = 0; i < global.size(); ++i) {
      const double d = std::hypot(global.x[2 * i] - px, global.x[2 * i + 1] - py);
      if (d < bd) bd = d, best = (int64_t)i;
    }
    return best;
  };
  for (int64_t p : {nearest(0.0105, 0.0045), nearest(0.012, 0.007), nearest(0.006, 0.0158), nearest(0.0, 0.0)}) {
    std::vector<double> u1 = u;
    for (PetscInt i = 0; i < n; ++i)
      if (layout.cloud.natural_id[i] == p) u1[2 * i] += 1e-5;
    ASSERT_EQ(sim.ComputeForceDensity(u1.data(), f1.data()), 0);
    std::vector<long long> changed;
    for (PetscInt i = 0; i < n; ++i)
      if (f1[2 * i] != f0[2 * i] || f1[2 * i + 1] != f0[2 * i + 1]) changed.push_back(layout.cloud.natural_id[i]);
    const std::set<int64_t> seen = GatherIds(PETSC_COMM_WORLD, changed);
    const Dependence        dep  = DependentPoints(global, families, p);
    std::vector<int64_t>    missing, leaked;
    std::set_difference(dep.physical.begin(), dep.physical.end(), seen.begin(), seen.end(), std::back_inserter(missing));
    std::set_difference(seen.begin(), seen.end(), dep.reach.begin(), dep.reach.end(), std::back_inserter(leaked));
    // Every physical dependant sees the perturbation (the ghosts carry it across
    // ranks), and nothing beyond two rings of bonds moves (nothing else is read).
    EXPECT_TRUE(missing.empty()) << "perturbed point " << p << ": " << missing.size()
                                 << " dependent points saw no change, first " << (missing.empty() ? -1 : missing[0]);
    EXPECT_TRUE(leaked.empty()) << "perturbed point " << p << ": " << leaked.size()
                                << " points beyond two rings changed, first " << (leaked.empty() ? -1 : leaked[0]);
    EXPECT_GT(dep.physical.size(), 10u);
  }
}
