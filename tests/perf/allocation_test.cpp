// No allocation inside a time step (docs/architecture.md, "Design rules that hold
// everywhere"): after a warm-up, a force
// evaluation and whole time steps, with failure on, grips, a probe and a history row
// every step, call the C++ allocator zero times. Counted by replacing the global
// operator new (PETSc and MPI allocate with malloc, which this does not see: their
// work vectors are created at set-up or on the first step, and this test is about
// the solver's own code).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <string>
#include <vector>

#include "bapd/solver/driver/simulation.hpp"
#include "mpi/test_scenes.hpp"

namespace {

std::atomic<long> allocations{0};
std::atomic<bool> counting{false};

// Allocations on this rank while `work` runs.
template <class F> long CountAllocations(F &&work)
{
  allocations = 0;
  counting    = true;
  work();
  counting = false;
  return allocations;
}

// The grips pull the free test sheet apart; bonds break past the critical stretch
// (with 3, none does in the first steps, so the breaking pass and the ring-1 exchange
// run and find nothing to do; a critical stretch just above 1 breaks bonds at once).
std::string LoadedSheet(const std::string &form, const std::string &critical_stretch = "3")
{
  return bapd_test::FreeSheetScene("allocation_output") +
         " -load_sets top,bottom -load_top_region top -load_top_x fixed -load_top_y stretch -load_top_y_scale 1"
         " -load_bottom_region bottom -load_bottom_x fixed -load_bottom_y fixed -load_schedule 0,1,0.1,1.3"
         " -failure_critical_stretch " + critical_stretch + " -probes tip -probe_tip_at 0.012,0.0065 -output_interval 1 -force_form " +
         form;
}

} // namespace

void *operator new(std::size_t size)
{
  if (counting) ++allocations;
  if (void *p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void *operator new[](std::size_t size) { return operator new(size); }
void  operator delete(void *p) noexcept { std::free(p); }
void  operator delete[](void *p) noexcept { std::free(p); }
void  operator delete(void *p, std::size_t) noexcept { std::free(p); }
void  operator delete[](void *p, std::size_t) noexcept { std::free(p); }

TEST(Allocation, CounterSeesAnAllocation)
{
  // The counter itself works: a vector that grows allocates.
  const long n = CountAllocations([] {
    std::vector<double> v(100);
    v.push_back(1.0);
  });
  EXPECT_GE(n, 1);
}

TEST(Allocation, ForceEvaluationAllocatesNothing)
{
  for (const char *form : {"bond_only", "energy_consistent"}) {
    ASSERT_EQ(bapd_test::SetOptions(LoadedSheet(form)), 0);
    bapd::Simulation sim(PETSC_COMM_WORLD);
    ASSERT_EQ(sim.Setup(), 0);
    const PetscInt      n = sim.layout().n_owned;
    std::vector<double> u(2 * n), f(2 * n);
    for (PetscInt i = 0; i < n; ++i) u[2 * i + 1] = 0.01 * sim.layout().cloud.x[2 * i + 1]; // 1 % stretch
    ASSERT_EQ(sim.ComputeForceDensity(u.data(), f.data()), 0); // warm-up
    PetscErrorCode ierr = 0;
    const long     count = CountAllocations([&] { ierr = sim.ComputeForceDensity(u.data(), f.data()); });
    ASSERT_EQ(ierr, 0);
    EXPECT_EQ(count, 0) << form << ": operator new calls in one force evaluation";
  }
}

TEST(Allocation, TimeStepsWithFailureAndHistoryAllocateNothing)
{
  for (const char *form : {"bond_only", "energy_consistent"}) {
    ASSERT_EQ(bapd_test::SetOptions(LoadedSheet(form)), 0);
    bapd::Simulation sim(PETSC_COMM_WORLD);
    ASSERT_EQ(sim.Setup(), 0);
    ASSERT_TRUE(sim.scene().failure);
    ASSERT_EQ(sim.scene().output_interval, 1); // a history row every step
    ASSERT_EQ(sim.Advance(5), 0);              // warm-up: the TS's first step sets up its work
    PetscErrorCode ierr  = 0;
    const long     count = CountAllocations([&] { ierr = sim.Advance(20); });
    ASSERT_EQ(ierr, 0);
    EXPECT_EQ(count, 0) << form << ": operator new calls in 20 time steps";
    PetscInt step;
    ASSERT_EQ(TSGetStepNumber(sim.ts(), &step), 0);
    EXPECT_EQ(step, 25);
  }
}

TEST(Allocation, TimeStepsInWhichBondsBreakAllocateNothing)
{
  // The breaking pass, the ring-1 exchange of intact masks and the recomputation of
  // the geometry of the points whose bonds broke (compute_bond_geometry) use only
  // work space sized at set-up.
  for (const char *form : {"bond_only", "energy_consistent"}) {
    ASSERT_EQ(bapd_test::SetOptions(LoadedSheet(form, "1.001")), 0);
    bapd::Simulation sim(PETSC_COMM_WORLD);
    ASSERT_EQ(sim.Setup(), 0);
    ASSERT_EQ(sim.Advance(5), 0); // warm-up
    PetscInt before, after;
    ASSERT_EQ(sim.BrokenBondCount(&before), 0);
    PetscErrorCode ierr  = 0;
    const long     count = CountAllocations([&] { ierr = sim.Advance(6); });
    ASSERT_EQ(ierr, 0);
    ASSERT_EQ(sim.BrokenBondCount(&after), 0);
    EXPECT_GT(after, before) << form << ": no bond broke in the counted steps";
    EXPECT_EQ(count, 0) << form << ": operator new calls in 6 time steps in which bonds break";
  }
}
