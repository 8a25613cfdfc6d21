// Typo suggestions for option names (see option_suggest.hpp).
#include "bapd/solver/input/option_suggest.hpp"

#include <algorithm>
#include <cctype>
#include <limits>

namespace bapd {

namespace {
char Lower(char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); }
} // namespace

std::size_t EditDistance(std::string_view a, std::string_view b)
{
  // Dynamic programme over prefixes, keeping three rows: d[i][j] is the distance
  // between a[0, i) and b[0, j); the swap term looks two rows back.
  const std::size_t        n = a.size(), m = b.size();
  std::vector<std::size_t> prev2(m + 1), prev(m + 1), cur(m + 1);
  for (std::size_t j = 0; j <= m; ++j) prev[j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = Lower(a[i - 1]) == Lower(b[j - 1]) ? 0 : 1;
      cur[j]                 = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost});
      if (i > 1 && j > 1 && Lower(a[i - 1]) == Lower(b[j - 2]) && Lower(a[i - 2]) == Lower(b[j - 1]))
        cur[j] = std::min(cur[j], prev2[j - 2] + 1);
    }
    std::swap(prev2, prev);
    std::swap(prev, cur);
  }
  return prev[m];
}

std::string SuggestOption(std::string_view name, const std::vector<std::string> &known)
{
  std::string lower(name);
  for (char &c : lower) c = Lower(c);
  const std::size_t dashes = lower.find_first_not_of('-');
  const std::string stem   = dashes == std::string::npos ? std::string() : lower.substr(dashes); // "mu" of "-mu"

  const std::size_t limit = std::max<std::size_t>(2, name.size() / 5);
  std::size_t       best  = std::numeric_limits<std::size_t>::max();
  std::string       choice;
  auto              consider = [&](std::size_t d, const std::string &candidate) {
    if (d < best || (d == best && candidate < choice)) {
      best   = d;
      choice = candidate;
    }
  };
  for (const std::string &k : known) {
    std::string kl(k);
    for (char &c : kl) c = Lower(c);
    const std::size_t d = EditDistance(lower, kl);
    if (d <= limit) consider(d, k);
    // "-mu" for "-material_mu": the name is a known one's last words. Ranked after
    // every real near-miss (distance limit + 1), shortest candidate first.
    else if (!stem.empty() && kl.size() > stem.size() + 1 && kl.compare(kl.size() - stem.size(), stem.size(), stem) == 0 && kl[kl.size() - stem.size() - 1] == '_')
      consider(limit + 1 + kl.size(), k);
  }
  return choice;
}

} // namespace bapd
