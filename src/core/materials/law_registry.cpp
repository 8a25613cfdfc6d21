// The run-time view of the law registry (law_registry.hpp), built once from the list.
#include "bapd/core/materials/law_registry.hpp"

#include <stdexcept>
#include <utility>

namespace bapd {
namespace {

template <class Law> LawEntry entry_of(ModelKind kind)
{
  LawEntry e{kind, Law::name, Law::title, {}, nullptr, nullptr};
  for (const LawOption<typename Law::Parameters> &o : Law::options) e.options.push_back({o.name, o.help, o.value});
  e.check   = [](const MaterialParameters &p) { return Law::check(ParametersOf<Law>(p)); };
  e.refusal = [](Formulation f) { return formulation_refusal<Law>(f); };
  if constexpr (Law::has_limit) {
    e.limit        = Law::limit;
    e.limit_option = Law::limit_option;
    e.I1bar_limit  = [](const MaterialParameters &p) { return Law::I1bar_limit(ParametersOf<Law>(p)); };
  }
  return e;
}

template <std::size_t... I> std::vector<LawEntry> all_entries(std::index_sequence<I...>)
{
  return {entry_of<std::tuple_element_t<I, RegisteredLaws>>(static_cast<ModelKind>(I))...};
}

} // namespace

const std::vector<LawEntry> &registered_laws()
{
  static const std::vector<LawEntry> laws = all_entries(std::make_index_sequence<registered_law_count>{});
  return laws;
}

const LawEntry &law_entry(ModelKind k)
{
  const std::size_t i = static_cast<std::size_t>(k);
  if (i >= registered_laws().size()) throw std::out_of_range("law_entry: not a registered law");
  return registered_laws()[i];
}

} // namespace bapd
