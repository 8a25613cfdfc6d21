// The law registry (law_registry.hpp): what it lists, that every entry is complete and
// consistent, and that every registered law, built through the registry alone
// (registered_laws() and with_model), has a stress that is the derivative of its
// energy in every formulation that accepts it. A new law passes these checks by
// being registered, without a test of its own.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <tuple>

#include "bapd/core/materials/models.hpp"
#include "materials/deformations.hpp"

namespace bapd {
namespace {

// The option names of a law's table (law.hpp: options) into names.
template <class Table> void insert_option_names(const Table &table, std::set<std::string> &names)
{
  for (const auto &o : table) names.insert(o.name);
}

TEST(LawRegistry, ListsTheRegisteredLawsInOrderWithUniqueNamesAndOptions)
{
  std::string           listed;
  std::set<std::string> names, options;
  for (std::size_t k = 0; k < registered_laws().size(); ++k) {
    const LawEntry &law = registered_laws()[k];
    listed += std::string(listed.empty() ? "" : " ") + law.name;
    EXPECT_EQ(static_cast<std::size_t>(law.kind), k);
    EXPECT_EQ(&law_entry(law.kind), &law);
    EXPECT_STREQ(to_string(law.kind), law.name);
    ModelKind back = static_cast<ModelKind>(registered_laws().size() - 1 - k);
    EXPECT_TRUE(parse(law.name, back));
    EXPECT_EQ(back, law.kind);
    EXPECT_TRUE(names.insert(law.name).second) << law.name << " registered twice";
    EXPECT_GT(std::string(law.title).size(), 10u) << law.name;
    for (const LawOptionEntry &o : law.options) {
      EXPECT_EQ(std::string(o.name).rfind("-material_", 0), 0u) << o.name; // the Material group
      EXPECT_NE(std::string(o.help).find('['), std::string::npos) << o.name << ": the help gives units";
      EXPECT_TRUE(options.insert(o.name).second) << o.name << " is an option of two laws";
    }
  }
  std::printf("registered laws: %s\n", listed.c_str());
  // The registry's order is the list's (law_list.hpp): -help's, the docs' and the tests'.
#define BAPD_LAW_ID_TEXT(type, id) " " #id
  EXPECT_EQ(listed, std::string(BAPD_REGISTERED_LAWS(BAPD_LAW_ID_TEXT)).substr(1));
#undef BAPD_LAW_ID_TEXT
  EXPECT_EQ(registered_laws().size(), registered_law_count);
  // Every law's own options, each law's from its own header's table.
  std::set<std::string> declared;
  std::apply([&](auto... law) { (insert_option_names(decltype(law)::options, declared), ...); }, RegisteredLaws{});
  EXPECT_EQ(options, declared);
}

// The scene's defaults (K = 1000 mu) and each law's own defaults.
MaterialParameters defaults()
{
  MaterialParameters p;
  p.D = 2.0 / (1000.0 * p.mu);
  return p;
}

TEST(LawRegistry, EveryLawAcceptsItsDefaultsAndNamesEachBadValue)
{
  for (const LawEntry &law : registered_laws()) {
    EXPECT_EQ(check_parameters(law.kind, defaults()), "") << law.name;
    for (const LawOptionEntry &o : law.options) {
      MaterialParameters p = defaults();
      p.values[o.index]           = std::numeric_limits<double>::quiet_NaN(); // no law accepts NaN
      const std::string problems = check_parameters(law.kind, p);
      EXPECT_NE(problems.find(o.name), std::string::npos) << law.name << ": " << problems;
      EXPECT_EQ(law.check(p), problems) << "mu and D are fine, so only the law's own line";
    }
    // every registered law runs in both formulations (and in 3D: Compressible3D, Ogden3D,
    // stress_energy_test)
    EXPECT_EQ(law.refusal(Formulation::plane_strain), "") << law.name;
    EXPECT_EQ(law.refusal(Formulation::plane_stress), "") << law.name;
    EXPECT_EQ(check_model(law.kind, Formulation::plane_stress, defaults()), "") << law.name;
  }
}

TEST(LawRegistry, EveryLawStressIsTheDerivativeOfItsEnergyThroughTheRegistry)
{
  for (const LawEntry &law : registered_laws())
    for (Formulation f : {Formulation::plane_stress, Formulation::plane_strain}) {
      if (!law.refusal(f).empty()) continue; // (checked above)
      std::mt19937 rng(31);
      const MaterialParameters p = defaults();
      int checked = with_model(law.kind, f, p, [&](const auto &model) {
        int n = 0;
        for (int sample = 0; sample < 60; ++sample, ++n) {
          const Mat2 F   = sample == 0 ? identity2() : test::random_F2(rng, 3.0);
          double     c33 = 0.0;
          Mat2       P;
          EXPECT_EQ(model.stress(F, c33, P), StressStatus::ok) << law.name << " sample " << sample;
          const double c33_solved = c33;
          auto         energy     = [&](const Mat2 &G) {
            double c = c33_solved, psi = 0.0;
            EXPECT_EQ(model.energy(G, c, psi), StressStatus::ok);
            return psi;
          };
          // central difference, h = 1e-6 max|F|: truncation (h/s_min)^2 ~ 1e-11, round-off
          // eps |psi| / h ~ 1e-9 of |P| (as in stress_energy_test); at rest P = 0 up to
          // round-off, against the floor mu.
          const Mat2 P_fd = test::energy_gradient(F, energy, 1e-6);
          EXPECT_LT(test::relative_difference(P, P_fd, p.mu), 1e-6) << law.name << " " << to_string(f) << " sample " << sample;
        }
        return n;
      });
      EXPECT_EQ(checked, 60);
    }
}

// Laws that the plane-stress solve must refuse (law.hpp, plane_stress.hpp): one that
// depends on I2bar and has a limit, one that is not convex, one in principal stretches
// without formulations of its own; and one of I2bar without a limit, which it accepts.
// Only their declarations matter here.
struct LawStub {
  struct Parameters {};
  static constexpr std::array<LawOption<Parameters>, 0> options = {};
  static constexpr LawVariables variables         = LawVariables::invariants;
  static constexpr bool         uses_I2bar        = false;
  static constexpr bool         convex_increasing = true;
  static constexpr bool         has_limit         = false;
};
struct WithI2bar : LawStub {
  static constexpr const char *name       = "with_i2bar";
  static constexpr bool        uses_I2bar = true;
};
struct WithI2barAndLimit : WithI2bar {
  static constexpr const char *name      = "with_i2bar_and_limit";
  static constexpr bool        has_limit = true;
};
struct NotConvex : LawStub {
  static constexpr const char *name              = "not_convex";
  static constexpr bool        convex_increasing = false;
};
struct InStretches : LawStub {
  static constexpr const char *name      = "in_stretches";
  static constexpr LawVariables variables = LawVariables::principal_stretches;
};

TEST(LawRegistry, PlaneStressRefusesLawsItCannotSolveWithAMessage)
{
  static_assert(accepts_plane_stress<Gent> && accepts_plane_stress<NeoHookean> && accepts_plane_stress<MooneyRivlin>);
  static_assert(accepts_plane_stress<WithI2bar> && !accepts_plane_stress<WithI2barAndLimit>);
  static_assert(!accepts_plane_stress<NotConvex> && !accepts_plane_stress<InStretches>);
  EXPECT_EQ(formulation_refusal<WithI2bar>(Formulation::plane_stress), "");
  const std::string i2 = formulation_refusal<WithI2barAndLimit>(Formulation::plane_stress);
  EXPECT_NE(i2.find("-material_model with_i2bar_and_limit with -material_formulation plane_stress"), std::string::npos) << i2;
  EXPECT_NE(i2.find("I2bar"), std::string::npos) << i2;
  EXPECT_NE(i2.find("use -material_formulation plane_strain"), std::string::npos) << i2;
  const std::string convex = formulation_refusal<NotConvex>(Formulation::plane_stress);
  EXPECT_NE(convex.find("convex and increasing in I1bar"), std::string::npos) << convex;
  EXPECT_EQ(formulation_refusal<NotConvex>(Formulation::plane_strain), "");
  EXPECT_EQ(formulation_refusal<WithI2barAndLimit>(Formulation::plane_strain), "");
  for (Formulation f : {Formulation::plane_stress, Formulation::plane_strain})
    EXPECT_NE(formulation_refusal<InStretches>(f).find("principal stretches"), std::string::npos);
}

} // namespace
// The store: each option has its own place, found by its name, holding the law's default;
// the summary prints each law's own values (Gent's as the scene summary always has).
TEST(LawRegistry, EachOptionHasItsOwnPlaceInTheStoreAndTheSummary)
{
  const MaterialParameters p;
  std::set<std::size_t>    places;
  for (const LawEntry &law : registered_laws())
    for (const LawOptionEntry &o : law.options) {
      EXPECT_TRUE(places.insert(o.index).second) << o.name;
      EXPECT_EQ(&p[o.name], &p.values[o.index]) << o.name;
      EXPECT_NE(parameter_summary(law.kind, p).find(std::string(o.name).substr(10) + " "), std::string::npos) << o.name;
    }
  EXPECT_EQ(places.size(), p.values.size());
  EXPECT_EQ(parameter_summary(ModelKind::gent, p), ", Jm 162.6");
  EXPECT_EQ(parameter_summary(ModelKind::neo_hookean, p), "");
  EXPECT_THROW(p["-material_nonsense"], std::out_of_range);
}

} // namespace bapd
