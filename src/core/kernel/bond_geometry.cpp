// The dimension-generic bond geometry (bond_geometry.hpp): usable K per bond and the
// stress correction C_i, instantiated for D = 2 and 3 (for D = 2 the operations of the
// earlier 2D bond_geometry.cpp, in its order); to_string / parse of StressCorrection.
#include "bapd/core/kernel/bond_geometry.hpp"

#include <algorithm>
#include <cmath>

#include "bapd/core/enum_words.hpp"

namespace bapd::nd {

namespace {

void check_family_volume(const PointCloud &cloud, std::size_t j)
{
  const double v = j < cloud.family_volume.size() ? cloud.family_volume[j] : std::nan("");
  if (!(v > 0) || !std::isfinite(v))
    throw std::invalid_argument("compute_bond_geometry: family volume V(H) of the point with natural id " +
                                std::to_string(cloud.natural_id[j]) + " is missing or not positive (" +
                                std::to_string(v) + "); call compute_family_volumes, and ship V(H) of ring-2 ghosts");
}

void check_state(const Families &families, const BondState &state)
{
  if (state.mask_words != families.mask_words || state.intact.size() != families.n_family * families.mask_words)
    throw std::invalid_argument("compute_bond_geometry: the bond state does not match the families");
}

void check_point_volumes(const PointCloud &cloud, const Families &fam, std::size_t i)
{
  if (fam.size(i) == 0) return;
  check_family_volume(cloud, i);
  for (std::size_t q = 0; q < fam.size(i); ++q) check_family_volume(cloud, static_cast<std::size_t>(fam.neighbour[fam.offsets[i] + q]));
}

// C_i from M_i (stress_correction.hpp): M_i^{-1} (tensor) or D / tr M_i I (scalar),
// I where M_i is not regular (no usable bond, all of them in a plane or a line).
template <int D> void set_correction(StressCorrection kind, const Mat<D> &M, double *C)
{
  const Mat<D> I = identity<D>();
  std::copy(I.begin(), I.end(), C);
  const double tr = trace<D>(M), d = det<D>(M);
  if (!regular<D>(d, tr)) return;
  if (kind == StressCorrection::scalar) {
    for (int r = 0; r < D; ++r) C[D * r + r] = static_cast<double>(D) / tr;
    return;
  }
  const Mat<D> adj = adjugate<D>(M);
  const double inv = 1.0 / d;
  for (int k = 0; k < D * D; ++k) C[k] = adj[k] * inv;
}

// Usable bits of point i (y = x: only K matters); returns the intact bonds not usable.
template <int D>
std::size_t point_geometry(const PointCloud &cloud, const Families &fam, const BondState &state, BondGeometry<D> &geo,
                           std::size_t i)
{
  const std::size_t    W = fam.mask_words, o = fam.offsets[i], m = fam.size(i);
  const std::uint64_t *intact = state.intact_mask(i);
  std::uint64_t       *usable = geo.usable.data() + i * W, *singular = geo.singular.data() + i * W;
  for (std::size_t w = 0; w < W; ++w) usable[w] = singular[w] = 0;
  if (m == 0) return 0;
  check_point_volumes(cloud, fam, i);
  const PointTotals<D> totals     = gather_point<D>(cloud, cloud.x.data(), fam, i, intact, geo.scratch);
  std::size_t          not_usable = 0;
  for (std::size_t q = 0; q < m; ++q) {
    if (!state.is_intact(i, q)) continue;
    const bool ok = bond_kinematics<D>(fam.ba(o + q), intact, W, geo.scratch, totals).usable;
    (ok ? usable : singular)[q / 64] |= std::uint64_t{1} << (q % 64);
    not_usable += !ok;
  }
  return not_usable;
}

// M_i over the bonds of i whose bits are set in `members` (with them as the intact set).
template <int D>
Mat<D> virial(const PointCloud &cloud, const Families &fam, const std::uint64_t *members, PointScratch<D> &s,
              std::size_t i)
{
  Mat<D>            M{};
  const std::size_t W = fam.mask_words, o = fam.offsets[i], m = fam.size(i);
  if (m == 0) return M;
  const PointTotals<D> totals = gather_point<D>(cloud, cloud.x.data(), fam, i, members, s);
  for (std::size_t q = 0; q < m; ++q) {
    if (!((members[q / 64] >> (q % 64)) & 1u)) continue;
    const BondKinematics<D> k = bond_kinematics<D>(fam.ba(o + q), members, W, s, totals);
    if (!k.usable) continue;
    // M_i += g_ij (x) xi_ij V_j, g the kernel's uncorrected force vector, bit for bit
    const double *xi = s.offset.data() + D * q, v = s.member[q][Member<D>::volume];
    double        g[D];
    force_vector<D>(k, force_scale<D>(k, totals, s.family_volume[q]), xi, g);
    for (int r = 0; r < D; ++r)
      for (int c = 0; c < D; ++c) M[D * r + c] += g[r] * xi[c] * v;
  }
  return M;
}

template <int D> void size_geometry(const PointCloud &cloud, const Families &families, BondGeometry<D> &geometry)
{
  const std::size_t W = families.mask_words;
  geometry.mask_words = W;
  geometry.usable.assign(families.n_family * W, 0);
  geometry.singular.assign(families.n_family * W, 0);
  geometry.scratch.reserve(families);
  geometry.reference_mask.assign(W, 0);
  geometry.done_in_pass.assign(families.n_family, 0);
  geometry.pass = 0;
  if (!geometry.corrected()) {
    geometry.correction.clear();
    return;
  }
  // C_i from M_i of the point's reference family: every bond that exists at t = 0
  // intact (pre-notch bonds never exist), whatever the bond state. Breaking does not
  // change C_i: the correction calibrates the discretisation, while a broken bond is
  // damage and must soften the point. Rebuilding C_i from the intact bonds would give
  // a point with most bonds broken a large M_i^{-1} (M_i -> 0), i.e. the full stress P
  // through a nearly detached point and a stiffness far above the one the stable step
  // was estimated with (the fracture rank-invariance scene diverged that way).
  geometry.correction.assign(D * D * families.n_family, 0.0);
  std::uint64_t *all = geometry.reference_mask.data();
  for (std::size_t i = 0; i < families.n_family; ++i) {
    check_point_volumes(cloud, families, i);
    for (std::size_t w = 0; w < W; ++w) all[w] = 0;
    for (std::size_t q = 0; q < families.size(i); ++q) all[q / 64] |= std::uint64_t{1} << (q % 64);
    set_correction<D>(geometry.stress_correction, virial<D>(cloud, families, all, geometry.scratch, i),
                      geometry.correction.data() + D * D * i);
  }
}

} // namespace

template <int D>
std::size_t compute_bond_geometry(const PointCloud &cloud, const Families &families, const BondState &state,
                                  BondGeometry<D> &geometry)
{
  check_state(families, state);
  size_geometry<D>(cloud, families, geometry);
  std::size_t not_usable = 0;
  for (std::size_t i = 0; i < families.n_family; ++i) not_usable += point_geometry<D>(cloud, families, state, geometry, i);
  return not_usable;
}

template <int D>
std::size_t compute_bond_geometry(const PointCloud &cloud, const Families &families, const BondState &state,
                                  BondGeometry<D> &geometry, const std::vector<std::size_t> &points)
{
  check_state(families, state);
  if (geometry.mask_words != families.mask_words || geometry.usable.size() != families.n_family * families.mask_words ||
      geometry.correction.size() != (geometry.corrected() ? D * D * families.n_family : 0))
    size_geometry<D>(cloud, families, geometry);
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
    not_usable += point_geometry<D>(cloud, families, state, geometry, i);
  }
  return not_usable;
}

template <int D>
BondShape<D> bond_shape(const PointCloud &cloud, const Families &families, const BondState &state, std::size_t i,
                        std::size_t q)
{
  BondShape<D> out;
  if (!state.is_intact(i, q)) return out;
  PointScratch<D> s;
  s.reserve(families);
  const std::uint64_t    *intact = state.intact_mask(i);
  const PointTotals<D>    totals = gather_point<D>(cloud, cloud.x.data(), families, i, intact, s);
  const BondKinematics<D> k      = bond_kinematics<D>(families.ba(families.offsets[i] + q), intact, families.mask_words, s, totals);
  if (!k.usable) return out;
  out.usable = true;
  for (int c = 0; c < sym_size<D>; ++c) out.shape_tensor_inv[c] = k.shape_tensor_inv[c];
  out.volume_fraction = k.volume / cloud.family_volume[i];
  out.force_scale     = force_scale<D>(k, totals, s.family_volume[q]);
  force_vector<D>(k, out.force_scale, s.offset.data() + D * q, out.force_vector.data());
  return out;
}

template <int D>
Mat<D> virial_tensor(const PointCloud &cloud, const Families &families, const BondState &state, std::size_t i)
{
  PointScratch<D> s;
  s.reserve(families);
  return virial<D>(cloud, families, state.intact_mask(i), s, i);
}

template std::size_t compute_bond_geometry<2>(const PointCloud &, const Families &, const BondState &, BondGeometry<2> &);
template std::size_t compute_bond_geometry<3>(const PointCloud &, const Families &, const BondState &, BondGeometry<3> &);
template std::size_t compute_bond_geometry<2>(const PointCloud &, const Families &, const BondState &, BondGeometry<2> &,
                                              const std::vector<std::size_t> &);
template std::size_t compute_bond_geometry<3>(const PointCloud &, const Families &, const BondState &, BondGeometry<3> &,
                                              const std::vector<std::size_t> &);
template BondShape<2> bond_shape<2>(const PointCloud &, const Families &, const BondState &, std::size_t, std::size_t);
template BondShape<3> bond_shape<3>(const PointCloud &, const Families &, const BondState &, std::size_t, std::size_t);
template Mat<2> virial_tensor<2>(const PointCloud &, const Families &, const BondState &, std::size_t);
template Mat<3> virial_tensor<3>(const PointCloud &, const Families &, const BondState &, std::size_t);

} // namespace bapd::nd

namespace bapd {

namespace {
constexpr EnumWords<StressCorrection::scalar> stress_correction_words{"none", "tensor", "scalar"};
} // namespace

const char *to_string(StressCorrection c) { return stress_correction_words(c); }

bool parse(const std::string &name, StressCorrection &c) { return stress_correction_words.parse(name, c); }

} // namespace bapd
