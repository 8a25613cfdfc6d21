#include "bapd/patch_correction.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "bapd/bond_state.hpp"
#include "bapd/nd/bond_geometry.hpp"

namespace bapd {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The kernel's force vector of every bond (BondOnlyForm::collect, nd/ba_force.hpp):
// g = C_i w K^{-1} xi for a usable bond, 0 for one that carries no force.
std::vector<double> force_vectors(const PointCloud &cloud, const Families &fam, const BondState &state,
                                  nd::BondGeometry<2> &geo)
{
  std::vector<double>  g(2 * fam.n_bonds(), 0.0);
  nd::PointScratch<2> &s = geo.scratch;
  const std::size_t    W = fam.mask_words;
  for (std::size_t i = 0; i < fam.n_family; ++i) {
    const std::size_t o = fam.offsets[i], m = fam.size(i);
    if (m == 0) continue;
    const std::uint64_t     *intact = state.intact_mask(i);
    const nd::PointTotals<2> totals = nd::gather_point<2>(cloud, cloud.x.data(), fam, i, intact, s);
    const Mat2               C      = geo.correction_of(i);
    for (std::size_t q = 0; q < m; ++q) {
      const std::uint64_t        *ba = fam.ba(o + q);
      const nd::BondKinematics<2> k  = nd::bond_kinematics<2>(ba, intact, W, s, totals);
      if (!k.usable) continue;
      Vec2 v;
      nd::force_vector<2>(k, nd::force_scale<2>(k, totals, s.family_volume[q]), s.offset.data() + 2 * q, v.data());
      g[2 * (o + q)]     = C[0] * v[0] + C[1] * v[1];
      g[2 * (o + q) + 1] = C[2] * v[0] + C[3] * v[1];
    }
  }
  return g;
}

// Points whose bonds leave an angular gap wider than a right angle (patch_correction.hpp).
std::vector<char> edge_points(const PointCloud &cloud, const Families &fam)
{
  std::vector<char>   edge(fam.n_family, 0);
  std::vector<double> angle;
  for (std::size_t i = 0; i < fam.n_family; ++i) {
    angle.clear();
    for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) {
      const std::size_t j = static_cast<std::size_t>(fam.neighbour[b]);
      angle.push_back(std::atan2(cloud.x[2 * j + 1] - cloud.x[2 * i + 1], cloud.x[2 * j] - cloud.x[2 * i]));
    }
    if (angle.size() < 3) {
      edge[i] = 1;
      continue;
    }
    std::sort(angle.begin(), angle.end());
    double gap = angle.front() + 2 * kPi - angle.back();
    for (std::size_t k = 1; k < angle.size(); ++k) gap = std::max(gap, angle[k] - angle[k - 1]);
    edge[i] = gap > 0.5 * kPi;
  }
  return edge;
}

// The boundary layer: edge points and every point bonded to one (one horizon deep),
// and the points with a bond that carries no force either way (their rows would not be
// those of A). One horizon, not the two that d_i reaches: on a lattice given as points
// (tensor correction, delta = 3.015 dx) the largest |d_i| over its terms is 0.84, 0.33,
// 0.16, 0.10 in the rows 0-3 from an edge, 0.030, 0.013, 0.005, 0.001 in rows 4-7 and
// round-off beyond: the layer keeps the traction, the rows after it lose a tail of at
// most 3 %, far below an irregular cloud's 8-20 %, and a specimen a few horizons wide
// keeps an interior (the dogbone's 10 mm gauge at delta ~ 3 mm).
std::vector<char> boundary_layer(const PointCloud &cloud, const Families &fam, const std::vector<double> &g)
{
  const std::vector<char> edge  = edge_points(cloud, fam);
  std::vector<char>       layer = edge;
  for (std::size_t i = 0; i < fam.n_family; ++i)
    if (edge[i])
      for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) layer[static_cast<std::size_t>(fam.neighbour[b])] = 1;
  for (std::size_t i = 0; i < fam.n_family; ++i)
    for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b)
      if (g[2 * b] == 0.0 && g[2 * b + 1] == 0.0) layer[i] = layer[static_cast<std::size_t>(fam.neighbour[b])] = 1;
  return layer;
}

// The force vector of bond b = (i -> j) with the correction: g_ij + h_ij (lambda
// empty: g_ij), 0 for a bond that carries no force (as in the kernel).
void corrected_vector(const PointCloud &cloud, const Families &fam, const std::vector<double> &g,
                      const std::vector<double> &lambda, std::size_t i, std::size_t b, double &v0, double &v1)
{
  v0 = g[2 * b];
  v1 = g[2 * b + 1];
  if (lambda.empty() || (v0 == 0.0 && v1 == 0.0)) return;
  const std::size_t j = static_cast<std::size_t>(fam.neighbour[b]);
  add_patch_term(lambda.data() + 2 * i, lambda.data() + 2 * j, cloud.x[2 * j] - cloud.x[2 * i],
                 cloud.x[2 * j + 1] - cloud.x[2 * i + 1], v0, v1);
}

// d_i = sum_j (g''_ij - g''_ji) V_j of point i with the corrected vectors above, and
// sum_j (|g_ij| + |g_ji|) V_j, the size of its terms.
void divergence(const PointCloud &cloud, const Families &fam, const std::vector<double> &g,
                const std::vector<double> &lambda, std::size_t i, double d[2], double &scale)
{
  d[0] = d[1] = scale = 0.0;
  for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) {
    const std::size_t j = static_cast<std::size_t>(fam.neighbour[b]), r = static_cast<std::size_t>(fam.reverse[b]);
    const double      v = cloud.volume[j];
    scale += (std::hypot(g[2 * b], g[2 * b + 1]) + std::hypot(g[2 * r], g[2 * r + 1])) * v;
    double a0, a1, c0, c1;
    corrected_vector(cloud, fam, g, lambda, i, b, a0, a1);
    corrected_vector(cloud, fam, g, lambda, j, r, c0, c1);
    d[0] += (a0 - c0) * v;
    d[1] += (a1 - c1) * v;
  }
}

// q = A p over the interior points (p = 0 in the boundary layer), A of patch_correction.hpp.
void apply(const PointCloud &cloud, const Families &fam, const std::vector<char> &layer, const std::vector<double> &p,
           std::vector<double> &q)
{
  for (std::size_t i = 0; i < fam.n_family; ++i) {
    double q0 = 0.0, q1 = 0.0;
    if (!layer[i])
      for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) {
        const std::size_t j  = static_cast<std::size_t>(fam.neighbour[b]);
        const double      x0 = cloud.x[2 * j] - cloud.x[2 * i], x1 = cloud.x[2 * j + 1] - cloud.x[2 * i + 1];
        const double      s  = 2.0 * cloud.volume[j] * ((p[2 * i] - p[2 * j]) * x0 + (p[2 * i + 1] - p[2 * j + 1]) * x1);
        q0 += s * x0;
        q1 += s * x1;
      }
    q[2 * i]     = cloud.volume[i] * q0;
    q[2 * i + 1] = cloud.volume[i] * q1;
  }
}

double dot(const std::vector<double> &a, const std::vector<double> &b)
{
  double s = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) s += a[k] * b[k];
  return s;
}

// x (0 on entry) solving A x = b by preconditioned conjugate gradients to round-off,
// ||r|| <= 1e-14 ||b||, at most `most` iterations; one thread, in index order, so the
// same bits on every run. apply(p, q): q = A p; precondition(r, z): z = M^-1 r. Returns
// the iterations taken.
template <class Apply, class Precondition>
std::size_t conjugate_gradients(const Apply &apply, const Precondition &precondition, const std::vector<double> &b,
                                std::vector<double> &x, std::size_t most)
{
  std::vector<double> r = b, z(b.size()), p(b.size()), q(b.size());
  precondition(r, z);
  p                  = z;
  double       rz    = dot(r, z);
  const double bnorm = std::sqrt(dot(b, b));
  std::size_t  it    = 0;
  for (; it < most && std::sqrt(dot(r, r)) > 1e-14 * bnorm; ++it) {
    apply(p, q);
    const double pq = dot(p, q);
    if (!(pq > 0.0)) break; // (A is positive definite: only at round-off)
    const double alpha = rz / pq;
    for (std::size_t k = 0; k < b.size(); ++k) {
      x[k] += alpha * p[k];
      r[k] -= alpha * q[k];
    }
    precondition(r, z);
    const double rz_next = dot(r, z), beta = rz_next / rz;
    rz                   = rz_next;
    for (std::size_t k = 0; k < b.size(); ++k) p[k] = z[k] + beta * p[k];
  }
  return it;
}

// What both solves start from: the kernel's force vectors g of every bond (reference
// state, nothing broken) and the boundary layer. Throws std::invalid_argument (naming
// `who`) unless the families are the whole cloud's.
struct SetupGeometry {
  std::vector<double> g;
  std::vector<char>   layer;
  SetupGeometry(const PointCloud &cloud, const Families &families, StressCorrection stress_correction, const char *who)
  {
    if (families.n_family != cloud.size() || families.reverse.size() != families.n_bonds())
      throw std::invalid_argument(std::string(who) + ": needs the families of every point of the cloud");
    BondState           state(families);
    nd::BondGeometry<2> geo;
    geo.stress_correction = stress_correction;
    nd::compute_bond_geometry<2>(cloud, families, state, geo);
    g     = force_vectors(cloud, families, state, geo);
    layer = boundary_layer(cloud, families, g);
  }
};

} // namespace

std::vector<double> compute_patch_correction(const PointCloud &cloud, const Families &families,
                                             StressCorrection stress_correction, PatchCorrectionReport *report)
{
  const std::size_t         n = families.n_family;
  const SetupGeometry       setup(cloud, families, stress_correction, "compute_patch_correction");
  const std::vector<double> &g = setup.g;
  const std::vector<char>   &layer = setup.layer;

  // The block-Jacobi preconditioner A_ii^{-1}; the defect without lambda.
  std::vector<double>   Dinv(4 * n, 0.0);
  const std::vector<double> none;
  PatchCorrectionReport out;
  for (std::size_t i = 0; i < n; ++i) {
    if (layer[i]) continue;
    ++out.interior;
    double d[2], scale;
    divergence(cloud, families, g, none, i, d, scale);
    out.before = std::max(out.before, std::hypot(d[0], d[1]) / scale);
    double a00 = 0.0, a01 = 0.0, a11 = 0.0;
    for (std::size_t k = families.offsets[i]; k < families.offsets[i + 1]; ++k) {
      const std::size_t j  = static_cast<std::size_t>(families.neighbour[k]);
      const double      x0 = cloud.x[2 * j] - cloud.x[2 * i], x1 = cloud.x[2 * j + 1] - cloud.x[2 * i + 1];
      const double      w  = 2.0 * cloud.volume[i] * cloud.volume[j];
      a00 += w * x0 * x0;
      a01 += w * x0 * x1;
      a11 += w * x1 * x1;
    }
    const double det = a00 * a11 - a01 * a01; // > 0: an interior point's bonds span the plane
    Dinv[4 * i]      = a11 / det;
    Dinv[4 * i + 1]  = Dinv[4 * i + 2] = -a01 / det;
    Dinv[4 * i + 3]  = a00 / det;
  }

  // A lambda = -V_i d_i by preconditioned conjugate gradients, to round-off.
  std::vector<double> lambda(2 * n, 0.0), b(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    if (layer[i]) continue;
    double d[2], scale;
    divergence(cloud, families, g, none, i, d, scale);
    b[2 * i]     = -cloud.volume[i] * d[0];
    b[2 * i + 1] = -cloud.volume[i] * d[1];
  }
  auto precondition = [&](const std::vector<double> &in, std::vector<double> &res) {
    for (std::size_t i = 0; i < n; ++i) {
      const double *D = Dinv.data() + 4 * i;
      res[2 * i]      = D[0] * in[2 * i] + D[1] * in[2 * i + 1];
      res[2 * i + 1]  = D[2] * in[2 * i] + D[3] * in[2 * i + 1];
    }
  };
  out.iterations = conjugate_gradients([&](const std::vector<double> &in, std::vector<double> &res) { apply(cloud, families, layer, in, res); },
                                       precondition, b, lambda, 20 * n + 100);
  double residual = 0.0; // the defect with lambda, evaluated as the kernel forms it
  for (std::size_t i = 0; i < n; ++i) {
    if (layer[i]) continue;
    double d[2], scale;
    divergence(cloud, families, g, lambda, i, d, scale);
    residual = std::max(residual, std::hypot(d[0], d[1]) / scale);
  }
  out.after = residual;
  for (std::size_t i = 0; i < n; ++i) { // the virial change sum_j h_ij (x) xi V_j (report only)
    double h[4] = {0, 0, 0, 0}, v[4] = {0, 0, 0, 0};
    for (std::size_t k = families.offsets[i]; k < families.offsets[i + 1]; ++k) {
      const std::size_t j  = static_cast<std::size_t>(families.neighbour[k]);
      const double      x0 = cloud.x[2 * j] - cloud.x[2 * i], x1 = cloud.x[2 * j + 1] - cloud.x[2 * i + 1], vj = cloud.volume[j];
      double            a0, a1;
      corrected_vector(cloud, families, g, lambda, i, k, a0, a1);
      const double e0 = a0 - g[2 * k], e1 = a1 - g[2 * k + 1];
      const double hv[4] = {e0 * x0, e0 * x1, e1 * x0, e1 * x1}, gv[4] = {g[2 * k] * x0, g[2 * k] * x1, g[2 * k + 1] * x0, g[2 * k + 1] * x1};
      for (int m = 0; m < 4; ++m) {
        h[m] += hv[m] * vj;
        v[m] += gv[m] * vj;
      }
    }
    const double vn = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
    if (vn > 0) out.virial = std::max(out.virial, std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2] + h[3] * h[3]) / vn);
  }
  if (!(residual < 1e-10))
    throw std::runtime_error("compute_patch_correction: the interior force under an affine motion stays at " +
                             std::to_string(residual) + " of its terms (the solve did not converge)");
  if (report) *report = out;
  return lambda;
}

namespace {

constexpr std::size_t kS = kVirialPatchStride;

// xi of bond b = (i -> j).
inline void bond_offset(const PointCloud &cloud, const Families &fam, std::size_t i, std::size_t b, double &x0, double &x1)
{
  const std::size_t j = static_cast<std::size_t>(fam.neighbour[b]);
  x0                  = cloud.x[2 * j] - cloud.x[2 * i];
  x1                  = cloud.x[2 * j + 1] - cloud.x[2 * i + 1];
}

// c_b of every bond from (mu, S): 0 where g_b = 0 (the kernel skips such a bond).
void bond_coefficients(const PointCloud &cloud, const Families &fam, const std::vector<double> &g,
                       const std::vector<double> &y, std::vector<double> &c)
{
  for (std::size_t i = 0; i < fam.n_family; ++i)
    for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) {
      double x0, x1;
      bond_offset(cloud, fam, i, b, x0, x1);
      const bool usable = g[2 * b] != 0.0 || g[2 * b + 1] != 0.0;
      c[b] = usable ? virial_patch_coefficient(y.data() + kS * i, y.data() + kS * static_cast<std::size_t>(fam.neighbour[b]), x0, x1)
                    : 0.0;
    }
}

// B c (each row times V_i): the patch rows V_i sum_j (c_ij + c_ji) xi V_j (interior
// points; 0 in the layer) and the virial rows V_i sum_j c_ij (x0^2, 2 x0 x1, x1^2) V_j.
void constraint_rows(const PointCloud &cloud, const Families &fam, const std::vector<char> &layer,
                     const std::vector<double> &c, std::vector<double> &out)
{
  for (std::size_t i = 0; i < fam.n_family; ++i) {
    double r[kS] = {0, 0, 0, 0, 0};
    for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) {
      double x0, x1;
      bond_offset(cloud, fam, i, b, x0, x1);
      const double v = cloud.volume[static_cast<std::size_t>(fam.neighbour[b])];
      const double p = (c[b] + c[static_cast<std::size_t>(fam.reverse[b])]) * v, q = c[b] * v;
      r[0] += p * x0;
      r[1] += p * x1;
      r[2] += q * x0 * x0;
      r[3] += 2.0 * q * x0 * x1;
      r[4] += q * x1 * x1;
    }
    for (std::size_t k = 0; k < kS; ++k) out[kS * i + k] = (k < 2 && layer[i]) ? 0.0 : cloud.volume[i] * r[k];
  }
}

// The inverse of the symmetric positive-definite m x m block a (m = 5, or 3 for the
// virial block of a layer point), in place, by Gauss-Jordan (no pivoting needed: SPD).
bool invert_block(double *a, std::size_t m)
{
  double inv[kS * kS] = {};
  for (std::size_t k = 0; k < m; ++k) inv[k * m + k] = 1.0;
  for (std::size_t k = 0; k < m; ++k) {
    const double piv = a[k * m + k];
    if (!(piv > 0.0)) return false;
    for (std::size_t l = 0; l < m; ++l) {
      a[k * m + l] /= piv;
      inv[k * m + l] /= piv;
    }
    for (std::size_t r = 0; r < m; ++r) {
      if (r == k) continue;
      const double f = a[r * m + k];
      for (std::size_t l = 0; l < m; ++l) {
        a[r * m + l] -= f * a[k * m + l];
        inv[r * m + l] -= f * inv[k * m + l];
      }
    }
  }
  for (std::size_t k = 0; k < m * m; ++k) a[k] = inv[k];
  return true;
}

} // namespace

std::vector<double> compute_virial_patch_correction(const PointCloud &cloud, const Families &families,
                                                    StressCorrection stress_correction, PatchCorrectionReport *report)
{
  const std::size_t         n = families.n_family, nb = families.n_bonds();
  const SetupGeometry       setup(cloud, families, stress_correction, "compute_virial_patch_correction");
  const std::vector<double> &g = setup.g;
  const std::vector<char>   &layer = setup.layer;
  const std::vector<double> none;

  // Right-hand side (-V_i d_i at interior points, 0 for the virial rows) and the
  // block-Jacobi preconditioner: the diagonal block of A at i, from the bonds of i
  // (c_ij holds mu_i and S_i, c_ji holds mu_i: a_ij, a_ji = the bond carries force).
  PatchCorrectionReport out;
  std::vector<double>   rhs(kS * n, 0.0), Dinv(kS * kS * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    double blk[kS * kS] = {};
    for (std::size_t b = families.offsets[i]; b < families.offsets[i + 1]; ++b) {
      const std::size_t j = static_cast<std::size_t>(families.neighbour[b]), r = static_cast<std::size_t>(families.reverse[b]);
      const double      a_ij = (g[2 * b] != 0.0 || g[2 * b + 1] != 0.0) ? 1.0 : 0.0;
      const double      a_ji = (g[2 * r] != 0.0 || g[2 * r + 1] != 0.0) ? 1.0 : 0.0;
      double            x0, x1;
      bond_offset(cloud, families, i, b, x0, x1);
      const double w = cloud.volume[i] * cloud.volume[j];
      const double e[kS] = {x0, x1, x0 * x0, 2.0 * x0 * x1, x1 * x1}; // d c_ij / d (mu_i, S_i)
      for (std::size_t k = 0; k < kS; ++k)
        for (std::size_t l = 0; l < kS; ++l) blk[k * kS + l] += w * a_ij * e[k] * e[l];
      for (std::size_t k = 0; k < 2; ++k) // c_ji = mu_i . xi_ij + ...: the patch rows only
        for (std::size_t l = 0; l < 2; ++l) blk[k * kS + l] += w * a_ji * e[k] * e[l];
    }
    double *D = Dinv.data() + kS * kS * i;
    if (layer[i]) { // the virial block only (mu_i = 0)
      double v[9];
      for (std::size_t k = 0; k < 3; ++k)
        for (std::size_t l = 0; l < 3; ++l) v[3 * k + l] = blk[(k + 2) * kS + l + 2];
      if (invert_block(v, 3))
        for (std::size_t k = 0; k < 3; ++k)
          for (std::size_t l = 0; l < 3; ++l) D[(k + 2) * kS + l + 2] = v[3 * k + l];
      continue;
    }
    ++out.interior;
    if (!invert_block(blk, kS))
      throw std::runtime_error("compute_virial_patch_correction: an interior point's bonds do not span its constraints");
    std::copy(blk, blk + kS * kS, D);
    double d[2], scale;
    divergence(cloud, families, g, none, i, d, scale);
    out.before       = std::max(out.before, std::hypot(d[0], d[1]) / scale);
    rhs[kS * i]      = -cloud.volume[i] * d[0];
    rhs[kS * i + 1]  = -cloud.volume[i] * d[1];
  }

  // A y = rhs by preconditioned conjugate gradients, to round-off.
  std::vector<double> y(kS * n, 0.0), c(nb);
  auto precondition = [&](const std::vector<double> &in, std::vector<double> &res) {
    for (std::size_t i = 0; i < n; ++i) {
      const double *D = Dinv.data() + kS * kS * i;
      for (std::size_t k = 0; k < kS; ++k) {
        double s = 0.0;
        for (std::size_t l = 0; l < kS; ++l) s += D[k * kS + l] * in[kS * i + l];
        res[kS * i + k] = s;
      }
    }
  };
  auto apply_A = [&](const std::vector<double> &in, std::vector<double> &res) {
    bond_coefficients(cloud, families, g, in, c);
    constraint_rows(cloud, families, layer, c, res);
  };
  out.iterations = conjugate_gradients(apply_A, precondition, rhs, y, 20 * n + 100);

  // What the kernel would form: the patch defect at interior points and the virial
  // change at every point, with h_ij = c_ij xi_ij on the force-carrying bonds.
  bond_coefficients(cloud, families, g, y, c);
  for (std::size_t i = 0; i < n; ++i) {
    double d[2] = {0, 0}, scale = 0, h[3] = {0, 0, 0}, v[4] = {0, 0, 0, 0};
    for (std::size_t b = families.offsets[i]; b < families.offsets[i + 1]; ++b) {
      const std::size_t j = static_cast<std::size_t>(families.neighbour[b]), rb = static_cast<std::size_t>(families.reverse[b]);
      double            x0, x1;
      bond_offset(cloud, families, i, b, x0, x1);
      const double vj = cloud.volume[j];
      scale += (std::hypot(g[2 * b], g[2 * b + 1]) + std::hypot(g[2 * rb], g[2 * rb + 1])) * vj;
      const double gn = std::hypot(g[2 * b], g[2 * b + 1]);
      if (gn > 0) out.term = std::max(out.term, std::abs(c[b]) * std::hypot(x0, x1) / gn);
      d[0] += (g[2 * b] - g[2 * rb] + (c[b] + c[rb]) * x0) * vj;
      d[1] += (g[2 * b + 1] - g[2 * rb + 1] + (c[b] + c[rb]) * x1) * vj;
      h[0] += c[b] * x0 * x0 * vj;
      h[1] += c[b] * x0 * x1 * vj;
      h[2] += c[b] * x1 * x1 * vj;
      v[0] += g[2 * b] * x0 * vj;
      v[1] += g[2 * b] * x1 * vj;
      v[2] += g[2 * b + 1] * x0 * vj;
      v[3] += g[2 * b + 1] * x1 * vj;
    }
    const double vn = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
    if (vn > 0) out.virial = std::max(out.virial, std::sqrt(h[0] * h[0] + 2 * h[1] * h[1] + h[2] * h[2]) / vn);
    if (!layer[i]) out.after = std::max(out.after, std::hypot(d[0], d[1]) / scale);
  }
  if (report) *report = out;
  if (!(out.after < 1e-10 && out.virial < 1e-10))
    throw std::runtime_error("compute_virial_patch_correction: the interior force under an affine motion stays at " +
                             std::to_string(out.after) + " of its terms and the virial changes by " +
                             std::to_string(out.virial) + " (the solve did not converge)");
  return y;
}

} // namespace bapd
