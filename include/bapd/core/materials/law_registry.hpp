#pragma once
// The registry of hyperelastic laws: every law the user can pick with
// -material_model, in one list. A new law is one header (law.hpp says what it holds:
// parameters, option names and help, checks, what it requires) plus one line in
// BAPD_REGISTERED_LAWS below; everything else is generated from that list:
//   ModelKind            the law's id, ModelKind::<id> (id = Law::name)
//   MaterialParameters   every law's parameter values (material.hpp), so that a scene
//                        holds them all and -help lists them all
//   LawAt<kind>          the law type of an id, for with_model (models.hpp)
//   registered_laws()    the run-time view: names, titles, options, checks
// Laws are picked at run time once, outside the hot loops (with_model), and are
// concrete types inside them.
#include <cstddef>
#include <string>
#include <tuple>
#include <vector>

#include "bapd/core/materials/arruda_boyce.hpp"
#include "bapd/core/materials/gent.hpp"
#include "bapd/core/materials/law.hpp"
#include "bapd/core/materials/mooney_rivlin.hpp"
#include "bapd/core/materials/neo_hookean.hpp"
#include "bapd/core/materials/ogden.hpp"
#include "bapd/core/materials/yeoh.hpp"

// X(type, id): the law's struct and its -material_model name (static_asserted equal
// to type::name below). One line per law; the order is the order of -help and docs.
#define BAPD_REGISTERED_LAWS(X)  \
  X(Gent, gent)                  \
  X(NeoHookean, neo_hookean)     \
  X(MooneyRivlin, mooney_rivlin) \
  X(Yeoh, yeoh)                  \
  X(ArrudaBoyce, arruda_boyce)   \
  X(Ogden, ogden)

namespace bapd {

enum class ModelKind {
#define BAPD_LAW_ID(type, id) id,
  BAPD_REGISTERED_LAWS(BAPD_LAW_ID)
#undef BAPD_LAW_ID
};

namespace detail {
template <class First, class... Laws> struct LawListAfter {
  using type = std::tuple<Laws...>;
};
constexpr bool same_name(const char *a, const char *b) { return *a == *b && (*a == '\0' || same_name(a + 1, b + 1)); }
} // namespace detail

#define BAPD_LAW_TYPE(type, id) , type
using RegisteredLaws = detail::LawListAfter<void BAPD_REGISTERED_LAWS(BAPD_LAW_TYPE)>::type;
#undef BAPD_LAW_TYPE
inline constexpr std::size_t registered_law_count = std::tuple_size_v<RegisteredLaws>;
template <ModelKind k> using LawAt = std::tuple_element_t<static_cast<std::size_t>(k), RegisteredLaws>;

#define BAPD_LAW_NAME_CHECK(type, id)                                                                        \
  static_assert(detail::same_name(type::name, #id), "BAPD_REGISTERED_LAWS: the id of " #type " must be its name");
BAPD_REGISTERED_LAWS(BAPD_LAW_NAME_CHECK)
#undef BAPD_LAW_NAME_CHECK

// The parameters of every registered law with the shared mu and D: what a scene
// holds (scene.material.mu, .D, .Jm, ...). A model takes the part it reads
// (ParametersOf<Law>, law.hpp). Option names, hence members, are unique across laws
// (LawRegistry tests check it).
#define BAPD_LAW_PARAMETERS(type, id) , type::Parameters
struct MaterialParameters : ElasticConstants BAPD_REGISTERED_LAWS(BAPD_LAW_PARAMETERS) {};
#undef BAPD_LAW_PARAMETERS

// The run-time view of one law, for option reading, help and checks.
struct LawOptionEntry {
  const char *name; // "-material_Jm"
  const char *help; // with units and the paper's value
  double MaterialParameters::*value;
};
struct LawEntry {
  ModelKind                   kind;
  const char                 *name;  // -material_model value
  const char                 *title; // one line for logs and help
  std::vector<LawOptionEntry> options;
  // One line per bad value of the law's own parameters (mu and D: check_parameters).
  std::string (*check)(const MaterialParameters &);
  // Empty when the law runs in that formulation, else why not (formulation_refusal).
  std::string (*refusal)(Formulation);
  // A law with a limit (has_limit, law.hpp: Gent, Arruda-Boyce): its name for messages,
  // the option that moves it and I1bar there. nullptr for a law without one.
  const char *limit        = nullptr;
  const char *limit_option = nullptr;
  double (*I1bar_limit)(const MaterialParameters &) = nullptr;
};
// Every registered law, in registry order (entry k has kind ModelKind(k)).
const std::vector<LawEntry> &registered_laws();
const LawEntry              &law_entry(ModelKind k);

} // namespace bapd
