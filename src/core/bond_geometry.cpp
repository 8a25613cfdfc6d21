#include "bapd/bond_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace bapd {

namespace {

void check_family_volume(const PointCloud &cloud, std::size_t j)
{
  const double v = j < cloud.family_volume.size() ? cloud.family_volume[j] : std::nan("");
  if (!(v > 0) || !std::isfinite(v))
    throw std::invalid_argument("compute_bond_geometry: family volume V(H) of the point with natural id " +
                                std::to_string(cloud.natural_id[j]) + " is missing or not positive (" +
                                std::to_string(v) +
                                "); call compute_family_volumes, and ship V(H) of ring-2 ghosts");
}

void check_state(const Families &families, const BondState &state)
{
  if (state.mask_words != families.mask_words || state.intact.size() != families.n_family * families.mask_words)
    throw std::invalid_argument("compute_bond_geometry: the bond state does not match the families");
}

void size_geometry(const Families &families, BondGeometry &geometry)
{
  geometry.mask_words = families.mask_words;
  geometry.usable.assign(families.n_family * families.mask_words, 0);
  geometry.singular.assign(families.n_family * families.mask_words, 0);
  geometry.scratch.reserve(families.max_family_size);
  geometry.done_in_pass.assign(families.n_family, 0);
  geometry.pass = 0;
}

// Usable bits of point i (y = x: only K matters); returns the intact bonds not usable.
std::size_t point_geometry(const PointCloud &cloud, const Families &fam, const BondState &state, BondGeometry &geo,
                           std::size_t i)
{
  PointScratch        &scratch = geo.scratch;
  const std::size_t    W = fam.mask_words, o = fam.offsets[i], m = fam.size(i);
  const std::uint64_t *intact = state.intact_mask(i);
  std::uint64_t       *usable = geo.usable.data() + i * W, *singular = geo.singular.data() + i * W;
  for (std::size_t w = 0; w < W; ++w) usable[w] = singular[w] = 0;
  if (m == 0) return 0;
  check_family_volume(cloud, i);
  for (std::size_t q = 0; q < m; ++q) check_family_volume(cloud, static_cast<std::size_t>(fam.neighbour[o + q]));

  const PointTotals totals = W == 1 ? detail::gather_point<1>(cloud, cloud.x.data(), fam, i, intact, scratch)
                                    : detail::gather_point<0>(cloud, cloud.x.data(), fam, i, intact, scratch);
  std::size_t      not_usable = 0;
  for (std::size_t q = 0; q < m; ++q) {
    if (!state.is_intact(i, q)) continue;
    const std::uint64_t *ba = fam.ba(o + q);
    const bool           ok = W == 1 ? detail::bond_kinematics<1>(ba, intact, 1, scratch, totals).usable
                                     : detail::bond_kinematics<0>(ba, intact, W, scratch, totals).usable;
    (ok ? usable : singular)[q / 64] |= std::uint64_t{1} << (q % 64);
    not_usable += !ok;
  }
  return not_usable;
}

} // namespace

std::size_t compute_bond_geometry(const PointCloud &cloud, const Families &families, const BondState &state,
                                  BondGeometry &geometry)
{
  check_state(families, state);
  size_geometry(families, geometry);
  std::size_t not_usable = 0;
  for (std::size_t i = 0; i < families.n_family; ++i)
    not_usable += point_geometry(cloud, families, state, geometry, i);
  return not_usable;
}

std::size_t compute_bond_geometry(const PointCloud &cloud, const Families &families, const BondState &state,
                                  BondGeometry &geometry, const std::vector<std::size_t> &points)
{
  check_state(families, state);
  if (geometry.mask_words != families.mask_words || geometry.usable.size() != families.n_family * families.mask_words)
    size_geometry(families, geometry);
  for (std::size_t i : points)
    if (i >= families.n_family)
      throw std::out_of_range("compute_bond_geometry: point " + std::to_string(i) + " has no family");
  // Each point once, so that the count is right: a point is marked with the number of
  // this pass (no copy of the list, no clearing; a pass that throws leaves marks that
  // the next pass does not read).
  if (++geometry.pass == 0) {
    std::fill(geometry.done_in_pass.begin(), geometry.done_in_pass.end(), 0);
    geometry.pass = 1;
  }
  std::size_t not_usable = 0;
  for (std::size_t i : points) {
    if (geometry.done_in_pass[i] == geometry.pass) continue;
    geometry.done_in_pass[i] = geometry.pass;
    not_usable += point_geometry(cloud, families, state, geometry, i);
  }
  return not_usable;
}

BondShape bond_shape(const PointCloud &cloud, const Families &families, const BondState &state, std::size_t i,
                     std::size_t q)
{
  BondShape out;
  if (!state.is_intact(i, q)) return out;
  PointScratch scratch;
  scratch.reserve(families.max_family_size);
  const std::size_t    W = families.mask_words, b = families.offsets[i] + q;
  const std::uint64_t *intact = state.intact_mask(i);
  const PointTotals    totals = W == 1 ? detail::gather_point<1>(cloud, cloud.x.data(), families, i, intact, scratch)
                                       : detail::gather_point<0>(cloud, cloud.x.data(), families, i, intact, scratch);
  const BondKinematics k = W == 1 ? detail::bond_kinematics<1>(families.ba(b), intact, 1, scratch, totals)
                                  : detail::bond_kinematics<0>(families.ba(b), intact, W, scratch, totals);
  if (!k.usable) return out;
  out.usable           = true;
  out.shape_tensor_inv = {k.shape_tensor_inv[0], k.shape_tensor_inv[1], k.shape_tensor_inv[2]};
  out.volume_fraction  = k.volume / cloud.family_volume[i];
  out.force_scale      = detail::force_scale(k, totals, scratch.family_volume[q]);
  const double d0 = scratch.offset[2 * q], d1 = scratch.offset[2 * q + 1], s = out.force_scale;
  out.force_vector = {s * (k.shape_tensor_inv[0] * d0 + k.shape_tensor_inv[1] * d1),
                      s * (k.shape_tensor_inv[1] * d0 + k.shape_tensor_inv[2] * d1)};
  return out;
}

} // namespace bapd
