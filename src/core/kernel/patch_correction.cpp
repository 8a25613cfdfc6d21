#include "bapd/core/kernel/patch_correction.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "bapd/core/kernel/bond_state.hpp"
#include "bapd/core/kernel/ba_force.hpp"
#include "bapd/core/kernel/bond_geometry.hpp"
#include "bapd/core/kernel/setup_solve.hpp"

namespace bapd {

namespace {

using setup_solve::conjugate_gradients;
using setup_solve::invert_block;
using setup_solve::kLargestBlock;

constexpr double kPi = 3.14159265358979323846;

// The setup solve for D = 2 and 3: one template, instantiated twice. For
// D = 2 every sum and product is the one of the 2D solve it replaced, in its order
// (-ffp-contract=off: the same bits; scripts/compare_binaries.sh's point-cloud scenes).

// |v| of a D-vector (std::hypot, as the 2D solve took it).
template <int D> double length(const double *v)
{
  if constexpr (D == 2) return std::hypot(v[0], v[1]);
  else return std::hypot(v[0], v[1], v[2]);
}

// v[0]^2 + ... + v[n-1]^2, left to right.
double sum_squares(const double *v, std::size_t n)
{
  double s = v[0] * v[0];
  for (std::size_t k = 1; k < n; ++k) s = s + v[k] * v[k];
  return s;
}

// xi of bond b = (i -> j).
template <int D> void bond_offset(const PointCloud &cloud, const Families &fam, std::size_t i, std::size_t b, double *xi)
{
  const std::size_t j = static_cast<std::size_t>(fam.neighbour[b]);
  for (int r = 0; r < D; ++r) xi[r] = cloud.x[D * j + r] - cloud.x[D * i + r];
}

// Whether bond b's force vector is not 0 (a bond that carries no force has g = 0).
template <int D> bool carries_force(const std::vector<double> &g, std::size_t b)
{
  for (int r = 0; r < D; ++r)
    if (g[D * b + r] != 0.0) return true;
  return false;
}

// The kernel's force vector of every bond (BondOnlyForm::collect, ba_force.hpp):
// g = C_i w K^{-1} xi for a usable bond, 0 for one that carries no force. The slow
// per-bond path of nd:: (bond_shape: the kernel's arithmetic), once at setup.
template <int D>
std::vector<double> force_vectors(const PointCloud &cloud, const Families &fam, const BondState &state,
                                  const nd::BondGeometry<D> &geo)
{
  std::vector<double> g(D * fam.n_bonds(), 0.0);
  for (std::size_t i = 0; i < fam.n_family; ++i) {
    const nd::Mat<D> C = geo.correction_of(i);
    for (std::size_t q = 0; q < fam.size(i); ++q) {
      if (!geo.is_usable(i, q)) continue;
      const nd::BondShape<D> k = nd::bond_shape<D>(cloud, fam, state, i, q);
      if (!k.usable) continue;
      const nd::Vec<D> &v = k.force_vector;
      const std::size_t b = fam.offsets[i] + q;
      for (int r = 0; r < D; ++r) {
        double s = C[D * r] * v[0];
        for (int c = 1; c < D; ++c) s = s + C[D * r + c] * v[c];
        g[D * b + r] = s;
      }
    }
  }
  return g;
}

// Points whose bonds leave an angular gap wider than a right angle (patch_correction.hpp).
// 2D: the widest gap between the bonds' angles. 3D: the same test as an empty cone, a
// direction n that every bond leaves at more than 45 degrees (in 2D: a gap > 90 degrees
// about n), looked for among 500 directions spread over the sphere (a Fibonacci
// lattice, about 9 degrees apart; a gap found is a gap, one missed is narrower than
// about 100 degrees). A point of a flat face has an empty half-space (180 degrees about
// its normal); one a spacing or more below it has bonds straight out to the face, so
// the edge points are the outer row, as in 2D.
std::vector<char> edge_points_2d(const PointCloud &cloud, const Families &fam)
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

std::vector<char> edge_points_3d(const PointCloud &cloud, const Families &fam)
{
  constexpr std::size_t kDirections = 500;
  const double          cos_cone    = std::sqrt(0.5); // cos 45 degrees
  std::vector<double>   n(3 * kDirections), e;
  for (std::size_t k = 0; k < kDirections; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / kDirections, r = std::sqrt(1.0 - z * z), a = k * kPi * (3.0 - std::sqrt(5.0));
    n[3 * k] = r * std::cos(a), n[3 * k + 1] = r * std::sin(a), n[3 * k + 2] = z;
  }
  std::vector<char> edge(fam.n_family, 0);
  for (std::size_t i = 0; i < fam.n_family; ++i) {
    e.clear();
    for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) {
      double xi[3];
      bond_offset<3>(cloud, fam, i, b, xi);
      const double l = length<3>(xi);
      for (int r = 0; r < 3; ++r) e.push_back(xi[r] / l);
    }
    if (e.size() < 3 * 4) {
      edge[i] = 1;
      continue;
    }
    for (std::size_t k = 0; k < kDirections && !edge[i]; ++k) {
      bool empty = true; // no bond within 45 degrees of n_k
      for (std::size_t m = 0; m < e.size() && empty; m += 3)
        empty = n[3 * k] * e[m] + n[3 * k + 1] * e[m + 1] + n[3 * k + 2] * e[m + 2] <= cos_cone;
      edge[i] = empty;
    }
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
template <int D> std::vector<char> boundary_layer(const PointCloud &cloud, const Families &fam, const std::vector<double> &g)
{
  const std::vector<char> edge  = D == 2 ? edge_points_2d(cloud, fam) : edge_points_3d(cloud, fam);
  std::vector<char>       layer = edge;
  for (std::size_t i = 0; i < fam.n_family; ++i)
    if (edge[i])
      for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) layer[static_cast<std::size_t>(fam.neighbour[b])] = 1;
  for (std::size_t i = 0; i < fam.n_family; ++i)
    for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b)
      if (!carries_force<D>(g, b)) layer[i] = layer[static_cast<std::size_t>(fam.neighbour[b])] = 1;
  return layer;
}

// The force vector v of bond b = (i -> j) with the correction: g_ij + h_ij (lambda
// empty: g_ij), 0 for a bond that carries no force (as in the kernel, whose
// nd::add_patch_term forms h_ij).
template <int D>
void corrected_vector(const PointCloud &cloud, const Families &fam, const std::vector<double> &g,
                      const std::vector<double> &lambda, std::size_t i, std::size_t b, double *v)
{
  for (int r = 0; r < D; ++r) v[r] = g[D * b + r];
  if (lambda.empty() || !carries_force<D>(g, b)) return;
  const std::size_t j = static_cast<std::size_t>(fam.neighbour[b]);
  double            xi[D];
  bond_offset<D>(cloud, fam, i, b, xi);
  nd::add_patch_term<D>(lambda.data() + D * i, lambda.data() + D * j, xi, v);
}

// d_i = sum_j (g''_ij - g''_ji) V_j of point i with the corrected vectors above, and
// sum_j (|g_ij| + |g_ji|) V_j, the size of its terms.
template <int D>
void divergence(const PointCloud &cloud, const Families &fam, const std::vector<double> &g,
                const std::vector<double> &lambda, std::size_t i, double *d, double &scale)
{
  for (int r = 0; r < D; ++r) d[r] = 0.0;
  scale = 0.0;
  for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) {
    const std::size_t j = static_cast<std::size_t>(fam.neighbour[b]), rb = static_cast<std::size_t>(fam.reverse[b]);
    const double      v = cloud.volume[j];
    scale += (length<D>(g.data() + D * b) + length<D>(g.data() + D * rb)) * v;
    double a[D], c[D];
    corrected_vector<D>(cloud, fam, g, lambda, i, b, a);
    corrected_vector<D>(cloud, fam, g, lambda, j, rb, c);
    for (int r = 0; r < D; ++r) d[r] += (a[r] - c[r]) * v;
  }
}

// q = A p over the interior points (p = 0 in the boundary layer), A of patch_correction.hpp.
template <int D>
void apply(const PointCloud &cloud, const Families &fam, const std::vector<char> &layer, const std::vector<double> &p,
           std::vector<double> &q)
{
  for (std::size_t i = 0; i < fam.n_family; ++i) {
    double qi[D] = {};
    if (!layer[i])
      for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) {
        const std::size_t j = static_cast<std::size_t>(fam.neighbour[b]);
        double            x[D];
        bond_offset<D>(cloud, fam, i, b, x);
        double t = (p[D * i] - p[D * j]) * x[0];
        for (int r = 1; r < D; ++r) t = t + (p[D * i + r] - p[D * j + r]) * x[r];
        const double s = 2.0 * cloud.volume[j] * t;
        for (int r = 0; r < D; ++r) qi[r] += s * x[r];
      }
    for (int r = 0; r < D; ++r) q[D * i + r] = cloud.volume[i] * qi[r];
  }
}

// What both solves start from: the kernel's force vectors g of every bond (reference
// state, nothing broken) and the boundary layer. Throws std::invalid_argument (naming
// `who`) unless the families are the whole cloud's.
template <int D> struct SetupGeometry {
  std::vector<double> g;
  std::vector<char>   layer;
  SetupGeometry(const PointCloud &cloud, const Families &families, StressCorrection stress_correction, const char *who)
  {
    if (families.n_family != cloud.size() || families.reverse.size() != families.n_bonds() ||
        cloud.x.size() != D * cloud.size())
      throw std::invalid_argument(std::string(who) + ": needs the families of every point of the cloud");
    BondState           state(families);
    nd::BondGeometry<D> geo;
    geo.stress_correction = stress_correction;
    nd::compute_bond_geometry<D>(cloud, families, state, geo);
    g     = force_vectors<D>(cloud, families, state, geo);
    layer = boundary_layer<D>(cloud, families, g);
  }
};

} // namespace

template <int D>
std::vector<double> compute_patch_correction(const PointCloud &cloud, const Families &families,
                                             StressCorrection stress_correction, PatchCorrectionReport *report)
{
  const std::size_t          n = families.n_family;
  const SetupGeometry<D>     setup(cloud, families, stress_correction, "compute_patch_correction");
  const std::vector<double> &g     = setup.g;
  const std::vector<char>   &layer = setup.layer;

  // The block-Jacobi preconditioner A_ii^{-1}; the defect without lambda.
  std::vector<double>       Dinv(D * D * n, 0.0);
  const std::vector<double> none;
  PatchCorrectionReport     out;
  for (std::size_t i = 0; i < n; ++i) {
    if (layer[i]) continue;
    ++out.interior;
    double d[D], scale;
    divergence<D>(cloud, families, g, none, i, d, scale);
    out.before = std::max(out.before, length<D>(d) / scale);
    double a[D * D] = {}; // A_ii = sum_j 2 V_i V_j xi (x) xi, its upper triangle
    for (std::size_t k = families.offsets[i]; k < families.offsets[i + 1]; ++k) {
      const std::size_t j = static_cast<std::size_t>(families.neighbour[k]);
      double            x[D];
      bond_offset<D>(cloud, families, i, k, x);
      const double w = 2.0 * cloud.volume[i] * cloud.volume[j];
      for (int r = 0; r < D; ++r)
        for (int c = r; c < D; ++c) a[D * r + c] += w * x[r] * x[c];
    }
    double *Di = Dinv.data() + D * D * i;
    if constexpr (D == 2) {
      const double det = a[0] * a[3] - a[1] * a[1]; // > 0: an interior point's bonds span the plane
      Di[0]            = a[3] / det;
      Di[1] = Di[2] = -a[1] / det;
      Di[3]         = a[0] / det;
    } else {
      for (int r = 0; r < D; ++r)
        for (int c = 0; c < r; ++c) a[D * r + c] = a[D * c + r];
      if (!invert_block(a, D)) // (an interior point's bonds span space)
        throw std::runtime_error("compute_patch_correction: an interior point's bonds do not span space");
      std::copy(a, a + D * D, Di);
    }
  }

  // A lambda = -V_i d_i by preconditioned conjugate gradients, to round-off.
  std::vector<double> lambda(D * n, 0.0), b(D * n);
  for (std::size_t i = 0; i < n; ++i) {
    if (layer[i]) continue;
    double d[D], scale;
    divergence<D>(cloud, families, g, none, i, d, scale);
    for (int r = 0; r < D; ++r) b[D * i + r] = -cloud.volume[i] * d[r];
  }
  auto precondition = [&](const std::vector<double> &in, std::vector<double> &res) {
    for (std::size_t i = 0; i < n; ++i) {
      const double *Di = Dinv.data() + D * D * i;
      for (int r = 0; r < D; ++r) {
        double s = Di[D * r] * in[D * i];
        for (int c = 1; c < D; ++c) s = s + Di[D * r + c] * in[D * i + c];
        res[D * i + r] = s;
      }
    }
  };
  out.iterations = conjugate_gradients([&](const std::vector<double> &in, std::vector<double> &res) { apply<D>(cloud, families, layer, in, res); },
                                       precondition, b, lambda, 20 * n + 100, &out.residual);
  double residual = 0.0; // the defect with lambda, evaluated as the kernel forms it
  for (std::size_t i = 0; i < n; ++i) {
    if (layer[i]) continue;
    double d[D], scale;
    divergence<D>(cloud, families, g, lambda, i, d, scale);
    residual = std::max(residual, length<D>(d) / scale);
  }
  out.after = residual;
  for (std::size_t i = 0; i < n; ++i) { // the virial change sum_j h_ij (x) xi V_j (report only)
    double h[D * D] = {}, v[D * D] = {};
    for (std::size_t k = families.offsets[i]; k < families.offsets[i + 1]; ++k) {
      const std::size_t j = static_cast<std::size_t>(families.neighbour[k]);
      const double      vj = cloud.volume[j];
      double            x[D], a[D], e[D];
      bond_offset<D>(cloud, families, i, k, x);
      corrected_vector<D>(cloud, families, g, lambda, i, k, a);
      for (int r = 0; r < D; ++r) e[r] = a[r] - g[D * k + r];
      const double gn = length<D>(g.data() + D * k);
      if (gn > 0) out.term = std::max(out.term, length<D>(e) / gn);
      for (int r = 0; r < D; ++r)
        for (int c = 0; c < D; ++c) {
          h[D * r + c] += e[r] * x[c] * vj;
          v[D * r + c] += g[D * k + r] * x[c] * vj;
        }
    }
    const double vn = std::sqrt(sum_squares(v, D * D));
    if (vn > 0) out.virial = std::max(out.virial, std::sqrt(sum_squares(h, D * D)) / vn);
  }
  if (!(residual < 1e-10))
    throw std::runtime_error("compute_patch_correction: the interior force under an affine motion stays at " +
                             std::to_string(residual) + " of its terms (the solve did not converge)");
  if (report) *report = out;
  return lambda;
}

namespace {

// (mu, S) a point: D + D(D+1)/2 numbers (5 in 2D, 9 in 3D), as the kernel reads them.
template <int D> constexpr std::size_t kS = nd::patch_stride<D>(true);
static_assert(kVirialPatchStride == kS<2>, "the kernel reads (mu, S) with stride D + sym_size<D>");
static_assert(kS<3> <= kLargestBlock, "invert_block holds the 3D virial block");

// c_ij of bond xi from y_i = (mu_i, S_i), y_j: (mu_i - mu_j) . xi + xi . S_i xi, the
// terms in the order of virial_patch_coefficient (patch_correction.hpp) and of
// nd::add_patch_term with virial.
template <int D> double patch_coefficient(const double *y_i, const double *y_j, const double *xi)
{
  double s = (y_i[0] - y_j[0]) * xi[0];
  for (int r = 1; r < D; ++r) s = s + (y_i[r] - y_j[r]) * xi[r];
  for (int r = 0; r < D; ++r)
    for (int c = r; c < D; ++c) {
      const double y = y_i[D + nd::sym_index<D>(r, c)];
      s              = s + (r == c ? y * xi[r] * xi[c] : 2.0 * y * xi[r] * xi[c]);
    }
  return s;
}

// d c_ij / d (mu_i, S_i): (xi, then xi_r xi_c for r <= c, off the diagonal twice).
template <int D> void coefficient_gradient(const double *xi, double *e)
{
  for (int r = 0; r < D; ++r) e[r] = xi[r];
  for (int r = 0; r < D; ++r)
    for (int c = r; c < D; ++c) e[D + nd::sym_index<D>(r, c)] = r == c ? xi[r] * xi[c] : 2.0 * xi[r] * xi[c];
}

// c_b of every bond from (mu, S): 0 where g_b = 0 (the kernel skips such a bond).
template <int D>
void bond_coefficients(const PointCloud &cloud, const Families &fam, const std::vector<double> &g,
                       const std::vector<double> &y, std::vector<double> &c)
{
  for (std::size_t i = 0; i < fam.n_family; ++i)
    for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) {
      double x[D];
      bond_offset<D>(cloud, fam, i, b, x);
      c[b] = carries_force<D>(g, b)
                 ? patch_coefficient<D>(y.data() + kS<D> * i, y.data() + kS<D> * static_cast<std::size_t>(fam.neighbour[b]), x)
                 : 0.0;
    }
}

// B c (each row times V_i): the patch rows V_i sum_j (c_ij + c_ji) xi V_j (interior
// points; 0 in the layer) and the virial rows V_i sum_j c_ij (xi_r xi_c, off the
// diagonal twice) V_j.
template <int D>
void constraint_rows(const PointCloud &cloud, const Families &fam, const std::vector<char> &layer,
                     const std::vector<double> &c, std::vector<double> &out)
{
  for (std::size_t i = 0; i < fam.n_family; ++i) {
    double r[kS<D>] = {};
    for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) {
      double x[D];
      bond_offset<D>(cloud, fam, i, b, x);
      const double v = cloud.volume[static_cast<std::size_t>(fam.neighbour[b])];
      const double p = (c[b] + c[static_cast<std::size_t>(fam.reverse[b])]) * v, q = c[b] * v;
      for (int k = 0; k < D; ++k) r[k] += p * x[k];
      for (int k = 0; k < D; ++k)
        for (int l = k; l < D; ++l) r[D + nd::sym_index<D>(k, l)] += k == l ? q * x[k] * x[l] : 2.0 * q * x[k] * x[l];
    }
    for (std::size_t k = 0; k < kS<D>; ++k) out[kS<D> * i + k] = (k < D && layer[i]) ? 0.0 : cloud.volume[i] * r[k];
  }
}

// What the kernel would form: the patch defect at interior points and the virial
// change at every point, with h_ij = c_ij xi_ij on the force-carrying bonds: the
// report's after, term and virial.
template <int D>
void report_kernel_virial_patch(const PointCloud &cloud, const Families &families, const std::vector<double> &g,
                                const std::vector<double> &c, const std::vector<char> &layer, PatchCorrectionReport &out)
{
  constexpr std::size_t T = nd::sym_size<D>; // a point's virial block
  const std::size_t     n = families.n_family;
  for (std::size_t i = 0; i < n; ++i) {
    double d[D] = {}, scale = 0, h[T] = {}, v[D * D] = {};
    for (std::size_t b = families.offsets[i]; b < families.offsets[i + 1]; ++b) {
      const std::size_t j = static_cast<std::size_t>(families.neighbour[b]), rb = static_cast<std::size_t>(families.reverse[b]);
      double            x[D];
      bond_offset<D>(cloud, families, i, b, x);
      const double vj = cloud.volume[j];
      scale += (length<D>(g.data() + D * b) + length<D>(g.data() + D * rb)) * vj;
      const double gn = length<D>(g.data() + D * b);
      if (gn > 0) out.term = std::max(out.term, std::abs(c[b]) * length<D>(x) / gn);
      for (int r = 0; r < D; ++r) d[r] += (g[D * b + r] - g[D * rb + r] + (c[b] + c[rb]) * x[r]) * vj;
      for (int r = 0; r < D; ++r)
        for (int k = r; k < D; ++k) h[nd::sym_index<D>(r, k)] += c[b] * x[r] * x[k] * vj;
      for (int r = 0; r < D; ++r)
        for (int k = 0; k < D; ++k) v[D * r + k] += g[D * b + r] * x[k] * vj;
    }
    const double vn = std::sqrt(sum_squares(v, D * D));
    double       hn = h[0] * h[0]; // |sum_j h_ij (x) xi V_j|, symmetric: off the diagonal twice
    for (int r = 0; r < D; ++r)
      for (int k = r; k < D; ++k) {
        const int s = nd::sym_index<D>(r, k);
        if (s > 0) hn = hn + (r == k ? h[s] * h[s] : 2 * h[s] * h[s]);
      }
    if (vn > 0) out.virial = std::max(out.virial, std::sqrt(hn) / vn);
    if (!layer[i]) out.after = std::max(out.after, length<D>(d) / scale);
  }
}

} // namespace

template <int D>
std::vector<double> compute_virial_patch_correction(const PointCloud &cloud, const Families &families,
                                                    StressCorrection stress_correction, PatchCorrectionReport *report)
{
  constexpr std::size_t      S = kS<D>, T = nd::sym_size<D>; // a point's numbers; its virial block
  const std::size_t          n = families.n_family, nb = families.n_bonds();
  const SetupGeometry<D>     setup(cloud, families, stress_correction, "compute_virial_patch_correction");
  const std::vector<double> &g     = setup.g;
  const std::vector<char>   &layer = setup.layer;
  const std::vector<double>  none;

  // Right-hand side (-V_i d_i at interior points, 0 for the virial rows) and the
  // block-Jacobi preconditioner: the diagonal block of A at i, from the bonds of i
  // (c_ij holds mu_i and S_i, c_ji holds mu_i: a_ij, a_ji = the bond carries force).
  PatchCorrectionReport out;
  std::vector<double>   rhs(S * n, 0.0), Dinv(S * S * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    double blk[S * S] = {};
    for (std::size_t b = families.offsets[i]; b < families.offsets[i + 1]; ++b) {
      const std::size_t j = static_cast<std::size_t>(families.neighbour[b]), r = static_cast<std::size_t>(families.reverse[b]);
      const double      a_ij = carries_force<D>(g, b) ? 1.0 : 0.0;
      const double      a_ji = carries_force<D>(g, r) ? 1.0 : 0.0;
      double            x[D], e[S];
      bond_offset<D>(cloud, families, i, b, x);
      const double w = cloud.volume[i] * cloud.volume[j];
      coefficient_gradient<D>(x, e);
      for (std::size_t k = 0; k < S; ++k)
        for (std::size_t l = 0; l < S; ++l) blk[k * S + l] += w * a_ij * e[k] * e[l];
      for (std::size_t k = 0; k < D; ++k) // c_ji = mu_i . xi_ij + ...: the patch rows only
        for (std::size_t l = 0; l < D; ++l) blk[k * S + l] += w * a_ji * e[k] * e[l];
    }
    double *Di = Dinv.data() + S * S * i;
    if (layer[i]) { // the virial block only (mu_i = 0)
      double v[T * T];
      for (std::size_t k = 0; k < T; ++k)
        for (std::size_t l = 0; l < T; ++l) v[T * k + l] = blk[(k + D) * S + l + D];
      if (invert_block(v, T))
        for (std::size_t k = 0; k < T; ++k)
          for (std::size_t l = 0; l < T; ++l) Di[(k + D) * S + l + D] = v[T * k + l];
      continue;
    }
    ++out.interior;
    if (!invert_block(blk, S))
      throw std::runtime_error("compute_virial_patch_correction: an interior point's bonds do not span its constraints");
    std::copy(blk, blk + S * S, Di);
    double d[D], scale;
    divergence<D>(cloud, families, g, none, i, d, scale);
    out.before = std::max(out.before, length<D>(d) / scale);
    for (int r = 0; r < D; ++r) rhs[S * i + r] = -cloud.volume[i] * d[r];
  }

  // A y = rhs by preconditioned conjugate gradients, to round-off.
  std::vector<double> y(S * n, 0.0), c(nb);
  auto precondition = [&](const std::vector<double> &in, std::vector<double> &res) {
    for (std::size_t i = 0; i < n; ++i) {
      const double *Di = Dinv.data() + S * S * i;
      for (std::size_t k = 0; k < S; ++k) {
        double s = 0.0;
        for (std::size_t l = 0; l < S; ++l) s += Di[k * S + l] * in[S * i + l];
        res[S * i + k] = s;
      }
    }
  };
  auto apply_A = [&](const std::vector<double> &in, std::vector<double> &res) {
    bond_coefficients<D>(cloud, families, g, in, c);
    constraint_rows<D>(cloud, families, layer, c, res);
  };
  out.iterations = conjugate_gradients(apply_A, precondition, rhs, y, 20 * n + 100, &out.residual);

  bond_coefficients<D>(cloud, families, g, y, c);
  report_kernel_virial_patch<D>(cloud, families, g, c, layer, out);
  if (report) *report = out;
  if (!(out.after < 1e-10 && out.virial < 1e-10))
    throw std::runtime_error("compute_virial_patch_correction: the interior force under an affine motion stays at " +
                             std::to_string(out.after) + " of its terms and the virial changes by " +
                             std::to_string(out.virial) + " (the solve did not converge)");
  return y;
}

template std::vector<double> compute_patch_correction<2>(const PointCloud &, const Families &, StressCorrection,
                                                         PatchCorrectionReport *);
template std::vector<double> compute_patch_correction<3>(const PointCloud &, const Families &, StressCorrection,
                                                         PatchCorrectionReport *);
template std::vector<double> compute_virial_patch_correction<2>(const PointCloud &, const Families &, StressCorrection,
                                                                PatchCorrectionReport *);
template std::vector<double> compute_virial_patch_correction<3>(const PointCloud &, const Families &, StressCorrection,
                                                                PatchCorrectionReport *);

std::string describe_patch_correction(const PatchCorrectionReport &r, bool virial)
{
  char text[512];
  std::snprintf(text, sizeof text,
                "Patch correction %s: %zu interior points; largest interior force under an affine motion %.2g -> %.2g of "
                "its terms, largest change of a point's virial %.2g\n"
                "  (solved on rank 0: %zu conjugate-gradient iterations, residual %.2g of the right-hand side; largest "
                "|h_ij|/|g_ij| %.2g)\n",
                virial ? "virial" : "on", r.interior, r.before, r.after, r.virial, r.iterations, r.residual, r.term);
  return text;
}

} // namespace bapd
