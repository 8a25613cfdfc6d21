// The run-time view of the law registry (law_registry.hpp), built once from the list,
// and the store of every law's values (material_parameters.hpp).
#include "bapd/core/materials/law_registry.hpp"

#include <stdexcept>
#include <utility>

namespace bapd {

template <class Law> std::size_t law_value_offset() { return law_value_start(law_kind<Law>()); }

namespace {

template <class Law> LawEntry entry_of(ModelKind kind)
{
  LawEntry          e{kind, Law::name, Law::title, {}, nullptr, nullptr, nullptr};
  const std::size_t first = law_value_start(kind);
  for (std::size_t i = 0; i < Law::options.size(); ++i)
    e.options.push_back({Law::options[i].name, Law::options[i].help, first + i});
  e.check   = [](const MaterialParameters &p) { return Law::check(ParametersOf<Law>(p)); };
  e.refusal = [](Formulation f) { return formulation_refusal<Law>(f); };
  e.summary = [](const MaterialParameters &p) { return law_summary<Law>(ParametersOf<Law>(p)); };
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

// Each law's defaults (its Parameters' initialisers) at its place in the store.
template <class Law> void put_defaults(std::vector<double> &values)
{
  const typename Law::Parameters defaults{};
  const std::size_t              first = law_value_offset<Law>();
  for (std::size_t i = 0; i < Law::options.size(); ++i) values[first + i] = defaults.*(Law::options[i].value);
}

template <std::size_t... I> std::vector<double> all_defaults(std::index_sequence<I...>)
{
  std::vector<double> values(law_value_count);
  (put_defaults<std::tuple_element_t<I, RegisteredLaws>>(values), ...);
  return values;
}

const LawOptionEntry *find_option(const std::string &option)
{
  for (const LawEntry &law : registered_laws())
    for (const LawOptionEntry &o : law.options)
      if (option == o.name) return &o;
  throw std::out_of_range("MaterialParameters: " + option + " is no registered law's option");
}

} // namespace

// The offsets of every registered law, here once (law.hpp declares the template).
#define BAPD_LAW_OFFSET(type, id) template std::size_t law_value_offset<type>();
BAPD_REGISTERED_LAWS(BAPD_LAW_OFFSET)
#undef BAPD_LAW_OFFSET

MaterialParameters::MaterialParameters() : values(all_defaults(std::make_index_sequence<registered_law_count>{})) {}

double       &MaterialParameters::operator[](const std::string &option) { return values[find_option(option)->index]; }
const double &MaterialParameters::operator[](const std::string &option) const { return values[find_option(option)->index]; }

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
