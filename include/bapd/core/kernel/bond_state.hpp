#pragma once
// Which bonds are intact (paper eq 7: gamma = 1). A broken bond (i, k) drops k out of
// every BA family of i (docs/method.md section 2): the kernel ANDs each BA mask with the
// point's intact mask, so breaking a bond is one bit, and the bond geometry of i
// (and of k) must then be recomputed (compute_bond_geometry on those points).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "bapd/core/geometry/family.hpp"

namespace bapd {

struct BondState {
  std::size_t                mask_words = 1;
  std::vector<std::uint64_t> intact; // mask_words per family point; bit q: the q-th bond is intact
  // Softening bonds (softening.hpp): d_ij of every bond in family order, its force and
  // energy scaled by 1 - d_ij; empty without softening (nothing scaled).
  std::vector<double> damage;

  BondState() = default;
  // Every bond of every family point intact (bits beyond a point's family size are 0).
  explicit BondState(const Families &families);

  const std::uint64_t *intact_mask(std::size_t i) const { return intact.data() + i * mask_words; }
  // d of the bonds from family offset o on, or nullptr without softening.
  const double        *damage_from(std::size_t o) const { return damage.empty() ? nullptr : damage.data() + o; }
  bool                 is_intact(std::size_t i, std::size_t q) const
  {
    return (intact[i * mask_words + q / 64] >> (q % 64)) & 1u;
  }
  // Broken directed bonds of points [0, n_points).
  std::size_t count_broken(const Families &families, std::size_t n_points) const;
};

// Breaks bond q of point i and, when its other end j has a family here (j < n_family),
// the reverse copy (j -> i), so both directed copies agree. Appends i (and j) to
// *touched: their bond geometry must be recomputed. Returns false (and touches
// nothing) if the bond was already broken.
bool break_bond(const Families &families, BondState &state, std::size_t i, std::size_t q,
                std::vector<std::size_t> *touched = nullptr);

} // namespace bapd
