// No allocation in a 3D force evaluation of the generic core (ba_force.hpp;
// docs/architecture.md, "Design rules that hold everywhere"): after a warm-up that
// sizes the workspace, both force forms, the assembly and the strain energy call the
// C++ allocator zero times. Counted by replacing the global operator new (a binary of
// its own, so that the count sees nothing but this).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <vector>

#include "bapd/core/materials/gent.hpp"
#include "bapd/core/materials/material.hpp"
#include "bapd/core/kernel/ba_force.hpp"
#include "bapd/core/materials/compressible_lanes.hpp"
#include "bapd/core/geometry/family.hpp"

namespace {

std::atomic<long> allocations{0};
std::atomic<bool> counting{false};

template <class F> long CountAllocations(F &&work)
{
  allocations = 0;
  counting    = true;
  work();
  counting = false;
  return allocations;
}

} // namespace

// The replacements below pair malloc / aligned_alloc with free, which is right; GCC
// sees `new T` meet free() once they are inlined and warns (a false positive for
// replaced global operators).
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

void *operator new(std::size_t size)
{
  if (counting) ++allocations;
  if (void *p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void *operator new[](std::size_t size) { return operator new(size); }
void *operator new(std::size_t size, std::align_val_t a)
{
  if (counting) ++allocations;
  const std::size_t al = static_cast<std::size_t>(a);
  if (void *p = std::aligned_alloc(al, (size + al - 1) / al * al)) return p;
  throw std::bad_alloc();
}
void *operator new[](std::size_t size, std::align_val_t a) { return operator new(size, a); }
void  operator delete(void *p) noexcept { std::free(p); }
void  operator delete[](void *p) noexcept { std::free(p); }
void  operator delete(void *p, std::size_t) noexcept { std::free(p); }
void  operator delete[](void *p, std::size_t) noexcept { std::free(p); }
void  operator delete(void *p, std::align_val_t) noexcept { std::free(p); }
void  operator delete[](void *p, std::align_val_t) noexcept { std::free(p); }
void  operator delete(void *p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void  operator delete[](void *p, std::size_t, std::align_val_t) noexcept { std::free(p); }

TEST(Allocation3D, CounterSeesAnAlignedAllocation)
{
  // The workspace's records are over-aligned: the counter sees that kind too.
  const long n = CountAllocations([] { bapd::nd::Workspace<3> ws; ws.point.member.resize(10); });
  EXPECT_GE(n, 1);
}

TEST(Allocation3D, ForceEvaluationAllocatesNothing)
{
  using namespace bapd;
  const double   dx    = 1e-3;
  PointCloud     cloud = nd::box_lattice<3>({8, 8, 8}, dx);
  const Families fam   = nd::build_families<3>(cloud, cloud.size(), 3.015 * dx);
  compute_family_volumes(cloud, fam);
  const BondState     state(fam);
  nd::BondGeometry<3> geo;
  geo.stress_correction = StressCorrection::tensor;
  nd::compute_bond_geometry<3>(cloud, fam, state, geo);
  MaterialParameters p;
  p.D = 2.0 / (100.0 * p.mu);
  const Gent3D                        gent{p};
  const nd::Compressible3DLanes<Gent> gent_lanes{ParametersOf<Gent>(p)};
  std::vector<double> y(cloud.x), t(3 * fam.n_bonds()), f(3 * cloud.size());
  for (std::size_t k = 0; k < y.size(); k += 3) y[k] *= 1.1; // 10 % stretch in x
  nd::Workspace<3> ws;
  auto check = [&](const auto &model, const char *name) {
    for (ForceForm form : {ForceForm::bond_only, ForceForm::energy_consistent}) {
      ASSERT_TRUE(nd::compute_bond_forces<3>(form, model, cloud, y.data(), fam, geo, state, nullptr, t.data(), ws).ok()); // warm-up
      KernelStats s;
      const long  count = CountAllocations([&] {
        s = nd::compute_bond_forces<3>(form, model, cloud, y.data(), fam, geo, state, nullptr, t.data(), ws);
        nd::assemble_force_density<3>(fam, cloud, t.data(), cloud.size(), f.data());
        nd::strain_energy<3>(model, cloud, y.data(), fam, geo, state, nullptr, cloud.size(), ws);
      });
      EXPECT_EQ(count, 0) << name << ": operator new calls in one 3D force evaluation";
      EXPECT_EQ(s.evaluated, fam.n_bonds()); // it did evaluate every bond
    }
  };
  check(gent, "Gent3D");
  check(gent_lanes, "Compressible3DLanes<Gent>");
}
