#pragma once
// The registry of hyperelastic laws: every law the user can pick with -material_model.
// A new law is one header (law.hpp says what it holds: parameters, option names and
// help, checks, what it requires) plus one line in BAPD_REGISTERED_LAWS (law_list.hpp)
// and its #include below; everything else is generated from that list:
//   ModelKind            the law's id, ModelKind::<id> (law_list.hpp)
//   RegisteredLaws       the law types in list order (LawAt<kind>: the type of an id),
//                        for with_model (models.hpp) and the typed tests
//   MaterialParameters   every law's values in one store (material_parameters.hpp),
//                        law_value_offset<Law> its place there
//   registered_laws()    the run-time view: names, titles, options, checks, summary
// Laws are picked at run time once, outside the hot loops (with_model), and are
// concrete types inside them.
#include <cstddef>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "bapd/core/materials/law.hpp"
#include "bapd/core/materials/law_list.hpp"
#include "bapd/core/materials/material_parameters.hpp"

#include "bapd/core/materials/arruda_boyce.hpp"
#include "bapd/core/materials/gent.hpp"
#include "bapd/core/materials/mooney_rivlin.hpp"
#include "bapd/core/materials/neo_hookean.hpp"
#include "bapd/core/materials/ogden.hpp"
#include "bapd/core/materials/yeoh.hpp"

namespace bapd {

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
// The id of a registered law: LawAt<law_kind<Law>()> is Law.
template <class Law, std::size_t I = 0> constexpr ModelKind law_kind()
{
  static_assert(I < registered_law_count, "law_kind: not a registered law (BAPD_REGISTERED_LAWS, law_list.hpp)");
  if constexpr (std::is_same_v<Law, std::tuple_element_t<I, RegisteredLaws>>) return static_cast<ModelKind>(I);
  else return law_kind<Law, I + 1>();
}

#define BAPD_LAW_NAME_CHECK(type, id)                                                                        \
  static_assert(detail::same_name(type::name, #id), "BAPD_REGISTERED_LAWS: the id of " #type " must be its name");
BAPD_REGISTERED_LAWS(BAPD_LAW_NAME_CHECK)
#undef BAPD_LAW_NAME_CHECK

// Every registered law's types through F: LawsAs<PlaneStress> is
// std::tuple<PlaneStress<Gent>, ...> (the typed tests' lists: law_types.hpp in tests).
template <template <class...> class F, class List = RegisteredLaws> struct LawsAsImpl;
template <template <class...> class F, class... Laws> struct LawsAsImpl<F, std::tuple<Laws...>> {
  using type = std::tuple<F<Laws>...>;
};
template <template <class...> class F> using LawsAs = typename LawsAsImpl<F>::type;

// The place of law k's first own value in MaterialParameters::values: the option counts
// of the laws before it.
template <std::size_t... I> constexpr std::size_t option_count_before(std::size_t k, std::index_sequence<I...>)
{
  return ((I < k ? std::tuple_element_t<I, RegisteredLaws>::options.size() : 0) + ... + 0);
}
constexpr std::size_t law_value_start(ModelKind k)
{
  return option_count_before(static_cast<std::size_t>(k), std::make_index_sequence<registered_law_count>{});
}
inline constexpr std::size_t law_value_count = law_value_start(static_cast<ModelKind>(registered_law_count - 1)) +
                                               std::tuple_element_t<registered_law_count - 1, RegisteredLaws>::options.size();

// The run-time view of one law, for option reading, help and checks.
struct LawOptionEntry {
  const char *name;  // "-material_Jm"
  const char *help;  // with units and the paper's value
  std::size_t index; // its value: MaterialParameters::values[index]
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
  // The law's own parameters for the scene summary (law.hpp: summary), ", Jm 162.6".
  std::string (*summary)(const MaterialParameters &);
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
