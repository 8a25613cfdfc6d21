#include "bapd/core/kernel/bond_state.hpp"

#include <stdexcept>
#include <string>

namespace bapd {

BondState::BondState(const Families &families) : mask_words(families.mask_words)
{
  intact.assign(families.n_family * mask_words, 0);
  for (std::size_t i = 0; i < families.n_family; ++i) {
    const std::size_t m = families.size(i);
    for (std::size_t q = 0; q < m; ++q) intact[i * mask_words + q / 64] |= std::uint64_t{1} << (q % 64);
  }
}

std::size_t BondState::count_broken(const Families &families, std::size_t n_points) const
{
  std::size_t broken = 0;
  for (std::size_t i = 0; i < n_points; ++i) {
    std::size_t alive = 0;
    for (std::size_t w = 0; w < mask_words; ++w)
      alive += static_cast<std::size_t>(__builtin_popcountll(intact[i * mask_words + w]));
    broken += families.size(i) - alive;
  }
  return broken;
}

bool break_bond(const Families &families, BondState &state, std::size_t i, std::size_t q,
                std::vector<std::size_t> *touched)
{
  if (i >= families.n_family || q >= families.size(i))
    throw std::out_of_range("break_bond: no bond " + std::to_string(q) + " at point " + std::to_string(i));
  if (!state.is_intact(i, q)) return false;
  const std::size_t W = state.mask_words;
  state.intact[i * W + q / 64] &= ~(std::uint64_t{1} << (q % 64));
  if (touched) touched->push_back(i);
  const std::size_t b = families.offsets[i] + q;
  if (families.reverse[b] >= 0) {
    const std::size_t j  = static_cast<std::size_t>(families.neighbour[b]);
    const std::size_t qr = static_cast<std::size_t>(families.reverse[b]) - families.offsets[j];
    state.intact[j * W + qr / 64] &= ~(std::uint64_t{1} << (qr % 64));
    if (touched) touched->push_back(j);
  }
  return true;
}

} // namespace bapd
