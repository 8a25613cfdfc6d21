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

// The grips pull the free test sheet apart; bonds break by the criterion `failure`: by
// default past the critical stretch 3, which none reaches in the first steps, so the
// breaking pass and the ring-1 exchange run and find nothing to do (a critical stretch
// just above 1 breaks bonds at once).
std::string LoadedSheet(const std::string &form, const std::string &failure = "-failure_critical_stretch 3")
{
  return bapd_test::FreeSheetScene("allocation_output") +
         " -load_sets top,bottom -load_top_region top -load_top_x fixed -load_top_y stretch -load_top_y_scale 1"
         " -load_bottom_region bottom -load_bottom_x fixed -load_bottom_y fixed -load_schedule 0,1,0.1,1.3 " +
         failure + " -probes tip -probe_tip_at 0.012,0.0065 -output_interval 1 -force_form " + form;
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
    ASSERT_TRUE(sim.scene().failure.enabled);
    ASSERT_EQ(sim.scene().output.interval, 1); // a history row every step
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
    ASSERT_EQ(bapd_test::SetOptions(LoadedSheet(form, "-failure_critical_stretch 1.001")), 0);
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

TEST(Allocation, AStepInWhichACascadeBreaksTheSheetAllocatesNothing)
{
  // With the fracture-energy criterion a step breaks in passes at the same positions
  // until none breaks (Failure::Cascade), and a point whose bonds break in several
  // passes is listed by each. The free sheet stretched affinely by 1.2 in y at t = 0
  // with Gamma = 0.25 J/m^2 breaks about 4 300 of its bonds in the first step, in two
  // passes, nearly every point losing bonds: the list of the points whose bonds broke
  // (one entry a point) and the released energy's scratch (one entry an owned point)
  // are sized at set-up for it. The first step allocates once whatever breaks (the
  // TS's work); so it is counted against the same first step with Gamma = 100 J/m^2,
  // where no bond breaks.
  struct Outcome {
    long     allocations = 0;
    PetscInt broken      = 0;
  };
  auto first_step = [](const std::string &failure, Outcome *outcome) {
    ASSERT_EQ(bapd_test::SetOptions(bapd_test::FreeSheetScene("allocation_output") + " " + failure), 0);
    bapd::Simulation sim(PETSC_COMM_WORLD);
    ASSERT_EQ(sim.Setup(), 0);
    const PetscInt n = sim.layout().n_owned;
    double        *x;
    ASSERT_EQ(VecGetArray(sim.state(), &x), 0);
    for (PetscInt i = 0; i < n; ++i) x[2 * i] = 0, x[2 * i + 1] = 0.2 * sim.layout().cloud.x[2 * i + 1]; // u; v stays 0
    ASSERT_EQ(VecRestoreArray(sim.state(), &x), 0);
    PetscErrorCode ierr   = 0;
    outcome->allocations = CountAllocations([&] { ierr = sim.Advance(1); });
    ASSERT_EQ(ierr, 0);
    ASSERT_EQ(sim.BrokenBondCount(&outcome->broken), 0);
  };
  Outcome intact, cascade, one_pass;
  first_step("-failure_fracture_energy 100", &intact);
  first_step("-failure_fracture_energy 0.25", &cascade);
  first_step("-failure_fracture_energy 0.25 -failure_passes 1", &one_pass);
  EXPECT_EQ(intact.broken, 0);
  EXPECT_GT(cascade.broken, 1000) << "the sheet was expected to break in the first step";
  EXPECT_GT(cascade.broken, one_pass.broken) << "the first step was expected to break in more than one pass";
  EXPECT_EQ(cascade.allocations, intact.allocations) << "operator new calls in a first step in which a cascade breaks the sheet";
}
