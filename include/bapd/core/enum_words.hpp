#pragma once
// The words of an enum's values (option values, log and CSV text) as one table: the
// word of value k at index k, so that to_string and parse read the same list and a
// value has one spelling. For an enum class of values 0, 1, ..., Last, one word each:
//   inline constexpr EnumWords<Softening::exponential> softening_words{"none", "linear", "exponential"};
#include <array>
#include <cstddef>
#include <string>

namespace bapd {

template <auto Last> struct EnumWords {
  using Enum                        = decltype(Last);
  static constexpr std::size_t size = static_cast<std::size_t>(Last) + 1;

  template <class... Words> constexpr EnumWords(Words... w) : words{w...}
  {
    static_assert(sizeof...(Words) == size, "EnumWords: one word per value of the enum, in the values' order");
  }

  // The word of value; "?" for a value outside the enum.
  constexpr const char *operator()(Enum value) const
  {
    const auto k = static_cast<std::size_t>(value);
    return k < size ? words[k] : "?";
  }
  // The value whose word is word; false, value untouched, for a word not in the table.
  bool parse(const std::string &word, Enum &value) const
  {
    for (std::size_t k = 0; k < size; ++k)
      if (word == words[k]) {
        value = static_cast<Enum>(k);
        return true;
      }
    return false;
  }

  std::array<const char *, size> words;
};

} // namespace bapd
