#pragma once
// Typo suggestions for option names: "-material_muu" -> "-material_mu".
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace bapd {

// Optimal-string-alignment distance between a and b, ignoring case: the number of
// single-character insertions, deletions, substitutions and swaps of two adjacent
// characters that turn one into the other ("widht" -> "width" is 1).
std::size_t EditDistance(std::string_view a, std::string_view b);

// The name in `known` that `name` most plausibly misspells, or "" when none is close.
// Close means an edit distance of at most max(2, length / 5), or `name` being a known
// name without its component prefix ("-mu" for "-material_mu"). Ties go to the
// alphabetically first name, so the answer never depends on the order of `known`.
std::string SuggestOption(std::string_view name, const std::vector<std::string> &known);

} // namespace bapd
