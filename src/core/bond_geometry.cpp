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
  geometry.reference_mask.assign(families.mask_words, 0);
  if (geometry.corrected()) geometry.correction.assign(4 * families.n_family, 0.0);
  else geometry.correction.clear();
}

// C_i from M_i (bond_geometry.hpp, docs/stress_consistency.md). M_i is dimensionless
// (K^{-1} xi (x) xi V has units 1) and close to I in the interior; near a boundary it
// loses some of its magnitude but stays regular while the point has two independent
// usable bonds. The test det M > shape_tensor_degeneracy (tr M)^2 is K's usability
// test (bond_geometry.hpp) applied to M: a rank-1 M (all usable bonds collinear) or
// M = 0 (none) gets C = I, i.e. the uncorrected force, which is then the only choice
// that does not divide by round-off.
void set_correction(StressCorrection kind, const double M[4], double *C)
{
  const double tr = M[0] + M[3], det = M[0] * M[3] - M[1] * M[2];
  C[0] = C[3] = 1.0;
  C[1] = C[2] = 0.0;
  if (!(tr > 0.0) || !(det > shape_tensor_degeneracy * tr * tr)) return;
  if (kind == StressCorrection::scalar) {
    C[0] = C[3] = 2.0 / tr;
    return;
  }
  const double inv = 1.0 / det;
  C[0]             = M[3] * inv;
  C[1]             = -M[1] * inv;
  C[2]             = -M[2] * inv;
  C[3]             = M[0] * inv;
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

// C_i of point i from M_i of its reference family: every bond that exists at t = 0
// intact (pre-notch bonds never exist), whatever the bond state. Breaking does not
// change C_i: the correction calibrates the discretisation, while a broken bond is
// damage and must soften the point. Rebuilding C_i from the intact bonds would give
// a point with most bonds broken a large M_i^{-1} (M_i -> 0), i.e. the full stress P
// through a nearly detached point and a stiffness far above the one the stable step
// was estimated with (the fracture rank-invariance scene diverged that way).
void point_correction(const PointCloud &cloud, const Families &fam, BondGeometry &geo, std::size_t i)
{
  PointScratch     &scratch = geo.scratch;
  const std::size_t W = fam.mask_words, o = fam.offsets[i], m = fam.size(i);
  std::uint64_t    *all = geo.reference_mask.data();
  for (std::size_t w = 0; w < W; ++w) all[w] = 0;
  for (std::size_t q = 0; q < m; ++q) all[q / 64] |= std::uint64_t{1} << (q % 64);
  double M[4] = {0.0, 0.0, 0.0, 0.0}; // virial tensor, in family order
  if (m > 0) {
    const PointTotals totals = W == 1 ? detail::gather_point<1>(cloud, cloud.x.data(), fam, i, all, scratch)
                                      : detail::gather_point<0>(cloud, cloud.x.data(), fam, i, all, scratch);
    for (std::size_t q = 0; q < m; ++q) {
      const std::uint64_t *ba = fam.ba(o + q);
      const BondKinematics k  = W == 1 ? detail::bond_kinematics<1>(ba, all, 1, scratch, totals)
                                       : detail::bond_kinematics<0>(ba, all, W, scratch, totals);
      if (!k.usable) continue;
      // M_i += g_ij (x) xi_ij V_j, g_ij = force_scale K^{-1} xi_ij: the kernel's g, bit for bit
      const Vec2   g  = detail::force_vector(k, totals, scratch, q);
      const double d0 = scratch.offset[2 * q], d1 = scratch.offset[2 * q + 1], v = scratch.shape[q].v[3];
      const double g0 = g[0], g1 = g[1];
      M[0] += g0 * d0 * v;
      M[1] += g0 * d1 * v;
      M[2] += g1 * d0 * v;
      M[3] += g1 * d1 * v;
    }
  }
  set_correction(geo.stress_correction, M, geo.correction.data() + 4 * i);
}

// Sizes the geometry and, with a correction, computes C_i of every family point.
void size_geometry_and_correction(const PointCloud &cloud, const Families &families, BondGeometry &geometry)
{
  size_geometry(families, geometry);
  if (!geometry.corrected()) return;
  for (std::size_t i = 0; i < families.n_family; ++i) {
    if (families.size(i) > 0) check_family_volume(cloud, i);
    for (std::size_t q = 0; q < families.size(i); ++q)
      check_family_volume(cloud, static_cast<std::size_t>(families.neighbour[families.offsets[i] + q]));
    point_correction(cloud, families, geometry, i);
  }
}

} // namespace

const char *to_string(StressCorrection c)
{
  switch (c) {
  case StressCorrection::none: return "none";
  case StressCorrection::tensor: return "tensor";
  case StressCorrection::scalar: return "scalar";
  }
  return "?";
}

bool parse(const std::string &name, StressCorrection &c)
{
  for (StressCorrection k : {StressCorrection::none, StressCorrection::tensor, StressCorrection::scalar})
    if (name == to_string(k)) {
      c = k;
      return true;
    }
  return false;
}

std::size_t compute_bond_geometry(const PointCloud &cloud, const Families &families, const BondState &state,
                                  BondGeometry &geometry)
{
  check_state(families, state);
  size_geometry_and_correction(cloud, families, geometry);
  std::size_t not_usable = 0;
  for (std::size_t i = 0; i < families.n_family; ++i)
    not_usable += point_geometry(cloud, families, state, geometry, i);
  return not_usable;
}

std::size_t compute_bond_geometry(const PointCloud &cloud, const Families &families, const BondState &state,
                                  BondGeometry &geometry, const std::vector<std::size_t> &points)
{
  check_state(families, state);
  if (geometry.mask_words != families.mask_words || geometry.usable.size() != families.n_family * families.mask_words ||
      geometry.correction.size() != (geometry.corrected() ? 4 * families.n_family : 0))
    size_geometry_and_correction(cloud, families, geometry);
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

Mat2 virial_tensor(const PointCloud &cloud, const Families &families, const BondState &state, std::size_t i)
{
  Mat2 M = {0.0, 0.0, 0.0, 0.0};
  for (std::size_t q = 0; q < families.size(i); ++q) {
    const BondShape shape = bond_shape(cloud, families, state, i, q);
    if (!shape.usable) continue;
    const std::size_t j  = static_cast<std::size_t>(families.neighbour[families.offsets[i] + q]);
    const double      d0 = cloud.x[2 * j] - cloud.x[2 * i], d1 = cloud.x[2 * j + 1] - cloud.x[2 * i + 1];
    const double      v = cloud.volume[j], g0 = shape.force_vector[0], g1 = shape.force_vector[1];
    M = M + Mat2{g0 * d0 * v, g0 * d1 * v, g1 * d0 * v, g1 * d1 * v};
  }
  return M;
}

} // namespace bapd
