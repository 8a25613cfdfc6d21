#pragma once
// The plane-stress formulation of a law (law.hpp): S33 = 0, C33 solved per call, one
// bond at a time (stress) or four (stress_lanes, for the bond kernel).
#include <array>
#include <cmath>
#include <limits>

#include "bapd/core/materials/hyperelastic_numerics.hpp"
#include "bapd/core/kernel/lanes.hpp"
#include "bapd/core/materials/law.hpp"
#include "bapd/core/kernel/tensor.hpp"

namespace bapd {

// Plane stress (the paper's case, eqs 27-34). F = diag(F~, lambda_3), c = C33.
// With a = tr C~, k = J~^2:  J = sqrt(c k),  q = J^{-2/3} = (c k)^{-1/3},
// I1bar(c) = (a + c) q.  C33 S33 = 0 is the scalar equation (eq 33)
//
//   f(c) = Gbar(c) t(c) + (1/D)(c k - 1) = 0,   Gbar = G(I1bar) q,  t = (2c - a)/3
//
// and then P~ = Gbar (F~ - c F~^{-T}) (eq 34). Because S33 = 2 dPsi/dc = 0 at the
// solution, P~ is exactly the derivative of the reduced energy Psi(F~, c(F~)).
//
// A law of I2bar too (Mooney-Rivlin: law.hpp, uses_I2bar) adds, with H = 2 dPsi_iso/dI2bar,
// I2 = det C~ + c tr C~ = k + a c and I2bar(c) = (k + a c) q^2 (so c dI2bar/dc = q^2 t2):
//
//   f(c) = Gbar t + Hbar(c) t2(c) + (1/D)(c k - 1),   Hbar = H(I2bar) q^2,  t2 = (a c - 2k)/3
//
// and the in-plane block of the 3D stress (hyperelastic.hpp) with P33 = 0 and the 2x2
// Cayley-Hamilton F~ C~ = a F~ - k F~^{-T} is
//
//   P~ = (Gbar + c Hbar) F~ - (c Gbar + (a c - k) Hbar) F~^{-T}.
//
// What it requires of the law (accepts_plane_stress, law.hpp; a law that does not meet
// it is refused by the registry with formulation_refusal's message, and PlaneStress<Law>
// does not compile for it):
// * Psi_iso is written in invariants, with G and its first four I1bar-derivatives
//   (modulus): the Faa di Bruno sums of residual_at and the fourth-order step use them.
//   A law of I2bar is separable, Psi_iso = W1(I1bar) + W2(I2bar), and gives H and its
//   first four I2bar-derivatives (modulus_I2bar) the same way;
// * Psi_iso is convex and increasing in I1bar (G > 0, G' >= 0) wherever it is finite,
//   and a law with a limit is finite exactly below one I1bar_limit; a law of I2bar has
//   W2 convex and nondecreasing (H >= 0, H' >= 0) and no limit: the facts below, one
//   root and its bracket, follow from that and fail without it (a non-convex law can
//   have several roots, and the solve would return one of them silently).
//
// Facts the solver relies on:
// * Psi is strictly convex in ln c (U is convex in ln J, and I1bar and I2bar, sums of
//   exponentials of ln c, are fed to convex increasing W1, W2), so f = 2 c dPsi/dc
//   is strictly increasing: there is one root. (f' = (G' q^2 t^2 + Gbar (4c+a)/9)/c
//   + (H' q^4 t2^2 + Hbar (a c + 4k)/9)/c + k/D, every term >= 0 and k/D > 0.)
// * The isochoric terms vanish at c = a/2 (I1bar) and c = 2k/a (I2bar; 2k/a <= J~ <=
//   a/2) and the volumetric one at c = 1/k, each increasing through its zero: the root
//   lies in [min(a/2, 2k/a, 1/k), max(a/2, 1/k)] (2k/a only for a law of I2bar).
// * I1bar(c) is least at c = a/2, where it is 3 (a / (2 J~))^{2/3}. A law with a limit
//   is finite on an interval around a/2; f -> -inf at its left end and +inf at its
//   right end, so the root is always inside it. A locked trial c counts as f = -inf
//   below a/2 and +inf above, which keeps the bisection consistent. If even the least
//   I1bar is beyond the limit, no thickness helps: chain_limit.
//
// The solve: Newton on f inside that bracket, bisecting when a step leaves it or
// fails to halve the step before last (Numerical Recipes' rtsafe). A Newton step
// h = -f/f' is corrected by the series reversion of the Taylor polynomial of f:
//   delta = h (1 - A2 h + (2 A2^2 - A3) h^2),   A_n = f^(n) / (n! f'),
// which leaves |f(c + delta)| = |f' h^4 (5 A2 (A2^2 - A3) + A4)| + O(h^5) (fourth
// order); far from the root (|A2 h| > 0.1) only the Chebyshev term -A2 h^2 is added,
// and beyond |A2 h| > 0.5 none. It starts from the incoming c33 when that lies in the
// bracket (the previous step's value), else from the incompressible 1/k. It stops when
//   |f| <= tol = 1e-13 (|Gbar t| + |(ck - 1)/D|) + 1e-12 mu c + 4 eps f' c,
// i.e. 1e-13 of the two terms that cancel at the root, or 1e-12 mu in S33 = f/c, plus
// the round-off floor set by the spacing of doubles near c.
//
// It also stops without evaluating again (the warm-started time step's usual exit):
// when the step is small, |delta| <= 1e-3 c and G changes by at most 1e-3 G over it,
// and the fourth-order term bounds what it leaves by tol / 2, i.e.
//   |f' h^4| (5 |A2| (A2^2 + |A3|) + |A4|) <= tol / 2
// (each term in absolute value, so a cancellation between them cannot hide a large
// one). Why that is a bound: f is built from powers of c (q, w, t, ck) and from
// G(I1bar), whose Taylor series in c converge with ratio |delta|/c (powers of c) and
// |delta| |dI1bar/dc| / gap = |delta| |dG/dc| / G (Gent: G = mu Jm / gap, so
// G^(n)/n! = G / gap^n); so every order beyond the fourth is at most ~1e-3 of the one
// before, and the O(h^5) rest is below 1e-2 of the bound. The point c + delta thus
// satisfies |f| <= tol, the stopping test of an evaluated point, and Gbar is carried
// to it by its fourth-order Taylor series (relative error (1e-3)^5 ~ 1e-15, below the
// O(tol) of the solve). The error of the warm start does not accumulate over time
// steps: each call evaluates f at its start. A warm start from the previous time step
// with F changed by up to ~5e-4 (|dc| / c up to ~5e-4) thus costs one evaluation;
// 1e-2 changes and cold starts take two or three.
//
// No cube root on the chain: the iterate is the pair (c, s), s = (ck)^{1/3} = J^{2/3},
// c = s^3 / k, so that J^{-2/3} = 1/s and 1/c = k/s^3 (one division). The start is the
// stored c33 moved to approximate_cbrt's s (by < 1.2e-6 of c; c33 is only a guess) or
// s = 1; a Newton point gets s from (1 + delta/c)^{1/3} by its series; only bisections
// and large steps (rare: cold starts, locked points) call libm's cbrt.
//
// Near the Gent limit with a finite D: past the incompressible limit the sheet
// thickens (J > 1) to keep I1bar < Jm + 3, and the stress rises on the bulk scale
// K = 2/D rather than blowing up. The tangent grows towards K, so wave speeds grow by
// up to sqrt(K / mu): a time step sized from the small-strain moduli can become
// unstable there. (Paper parameters, K = 1e4 mu, pure shear: max |dP~/dF~| is 4 mu at
// rest, 1.6 mu at lambda = 5.125, 10 mu at 10 and 174 mu at 12.5.)

// f and its first four c-derivatives, and Gbar with its own (T = double or Lanes).
template <class T> struct PlaneStressResidualOf {
  MaskOf<T>        admissible{}; // false: the law is locked at this c (f = -inf/+inf)
  std::array<T, 5> f{};          // d^n f / dc^n
  std::array<T, 5> shear{};      // d^n Gbar / dc^n
  std::array<T, 5> shear_I2{};   // d^n Hbar / dc^n (laws of I2bar; else 0)
  T                scale{};      // |Gbar t| + |Hbar t2| + |(c k - 1)/D|
  T                dG_dc{};      // |dG/dI1bar dI1bar/dc|: G changes by this per unit c
  T                G{};          // G (at this c)
  T                dH_dc{};      // |dH/dI2bar dI2bar/dc|, and H (laws of I2bar; else 0)
  T                H{};
};
using PlaneStressResidual = PlaneStressResidualOf<double>;

// What one Newton evaluation decides (PlaneStress::step).
template <class T> struct PlaneStressStepOf {
  MaskOf<T> converged{}; // |f| <= tol (or the bracket is at round-off): c is the root
  MaskOf<T> accepted{};  // the corrected step is taken unevaluated: c + delta is the root
  T         c33{}, shear{}; // the root and Gbar there, where converged or accepted
  T         shear_I2{};     // Hbar there (laws of I2bar)
  T         lo{}, hi{};  // the bracket, narrowed by this evaluation
  T         delta{};     // the corrected Newton step
};

struct PlaneStressSolution {
  StressStatus status      = StressStatus::ok;
  double       c33         = 0.0; // C33 = lambda_3^2 with S33 = 0
  double       shear       = 0.0; // Gbar = G J^{-2/3}: P~ = Gbar (F~ - C33 F~^{-T})
  double       shear_I2    = 0.0; // Hbar = H J^{-4/3} (laws of I2bar; P~: see above)
  int          evaluations = 0;   // residual evaluations (the iteration count)
};

template <class Law> struct PlaneStress {
  static_assert(accepts_plane_stress<Law>, "PlaneStress: the law does not meet the solve's requirements (see above)");
  ParametersOf<Law>    p;
  static constexpr int max_iterations = 60;
  // stress_lanes() exists: the bond kernel hands this model lane_count (lanes.hpp) bonds at a time.
  static constexpr bool has_lanes = true;

  // f(c) and its derivatives for a = tr C~, k = J~^2 (inv_D = 1/D).
  // With q = (ck)^{-1/3} and w = c q, both powers of c: q^(n) and w^(n) are q and w
  // times constants over c^n; I1bar = a q + w; Gbar = G(I1bar) q by Faa di Bruno and
  // Leibniz; f = Gbar t + (ck - 1)/D with t' = 2/3, t'' = 0.
  PlaneStressResidual residual(double a, double k, double inv_D, double c) const
  {
    return residual_at(a, k, inv_D, c, std::cbrt(c * k));
  }

  // The same with s = (ck)^{1/3} given (the solve carries it along with c = s^3 / k):
  // q = 1/s and 1/c = k q^3, one division and no cube root. Where the law is locked
  // (admissible false) the values are finite and meaningless.
  template <class T> PlaneStressResidualOf<T> residual_at(T a, T k, double inv_D, T c, T s) const
  {
    PlaneStressResidualOf<T> r;
    const T                  q = 1.0 / s, u = k * q * q * q, w = c * q;
    ModulusOf<T>             G;
    r.admissible = Law::modulus(p, InvariantsOf<T>{a * q + w}, G);
    const T u2 = u * u, u3 = u2 * u, u4 = u2 * u2;
    // q ~ c^{-1/3}, w ~ c^{2/3}: q^(n) = q u^n prod_{m<n} (-1/3 - m), w^(n) likewise
    const T q1 = q * u * (-1.0 / 3.0), q2 = q * u2 * (4.0 / 9.0), q3 = q * u3 * (-28.0 / 27.0),
            q4 = q * u4 * (280.0 / 81.0);
    // I1bar = a q + w: its c-derivatives
    const T I1 = a * q1 + w * u * (2.0 / 3.0);
    const T I2 = a * q2 + w * u2 * (-2.0 / 9.0);
    const T I3 = a * q3 + w * u3 * (8.0 / 27.0);
    const T I4 = a * q4 + w * u4 * (-56.0 / 81.0);
    T dG_dc;
    r.shear = modulus_times_power(G, {I1, I2, I3, I4}, {q, q1, q2, q3, q4}, dG_dc); // Gbar = G q
    const T t = (2.0 * c - a) * (1.0 / 3.0);
    const T iso = r.shear[0] * t, vol = (c * k - 1.0) * inv_D;
    r.f     = {iso + vol, r.shear[1] * t + (2.0 / 3.0) * r.shear[0] + k * inv_D,
               r.shear[2] * t + (4.0 / 3.0) * r.shear[1], r.shear[3] * t + 2.0 * r.shear[2],
               r.shear[4] * t + (8.0 / 3.0) * r.shear[3]};
    r.scale = lane_abs(iso) + lane_abs(vol);
    r.dG_dc = lane_abs(dG_dc);
    r.G     = G[0];
    if constexpr (Law::uses_I2bar) {
      // I2bar = k v + a z, v = q^2 ~ c^{-2/3}, z = c q^2 ~ c^{1/3}: v^(n), z^(n) as q^(n)
      const T v = q * q, z = w * q;
      const T v1 = v * u * (-2.0 / 3.0), v2 = v * u2 * (10.0 / 9.0), v3 = v * u3 * (-80.0 / 27.0),
              v4 = v * u4 * (880.0 / 81.0);
      const T z1 = z * u * (1.0 / 3.0), z2 = z * u2 * (-2.0 / 9.0), z3 = z * u3 * (10.0 / 27.0),
              z4 = z * u4 * (-80.0 / 81.0);
      const T J1 = k * v1 + a * z1, J2 = k * v2 + a * z2, J3 = k * v3 + a * z3, J4 = k * v4 + a * z4;
      ModulusOf<T> H;
      Law::modulus_I2bar(p, InvariantsOf<T>{a * q + w, k * v + a * z}, H);
      T dH_dc;
      r.shear_I2 = modulus_times_power(H, {J1, J2, J3, J4}, {v, v1, v2, v3, v4}, dH_dc); // Hbar = H v
      // f += Hbar t2, t2 = (a c - 2k)/3: t2' = a/3, t2'' = 0
      const T t2 = (a * c - 2.0 * k) * (1.0 / 3.0), a3 = a * (1.0 / 3.0), iso2 = r.shear_I2[0] * t2;
      r.f[0] += iso2;
      r.f[1] += r.shear_I2[1] * t2 + a3 * r.shear_I2[0];
      r.f[2] += r.shear_I2[2] * t2 + 2.0 * a3 * r.shear_I2[1];
      r.f[3] += r.shear_I2[3] * t2 + 3.0 * a3 * r.shear_I2[2];
      r.f[4] += r.shear_I2[4] * t2 + 4.0 * a3 * r.shear_I2[3];
      r.scale += lane_abs(iso2);
      r.dH_dc = lane_abs(dH_dc);
      r.H     = H[0];
    }
    return r;
  }

  // The S33 = 0 solve, with diagnostics. c33_guess <= 0: no warm start.
  PlaneStressSolution solve(const Mat2 &F, double c33_guess) const
  {
    const double Jt = det(F);
    return solve(F, Jt, Jt > 0.0 ? 1.0 / Jt : 0.0, c33_guess); // no 1/0 under -fp_trap
  }

  StressStatus stress(const Mat2 &F, double &c33, Mat2 &P) const
  {
    const double              Jt = det(F), inv_Jt = Jt > 0.0 ? 1.0 / Jt : 0.0;
    const PlaneStressSolution s = solve(F, Jt, inv_Jt, c33);
    if (s.status != StressStatus::ok) {
      P = {};
      return s.status;
    }
    c33 = s.c33;
    if constexpr (Law::uses_I2bar) { // P~ = (Gbar + c Hbar) F~ - (c Gbar + (a c - k) Hbar) F~^{-T} (see above)
      const double a = F[0] * F[0] + F[1] * F[1] + F[2] * F[2] + F[3] * F[3];
      const double g = s.shear + s.c33 * s.shear_I2;
      const double b = (s.c33 * s.shear + (a * s.c33 - Jt * Jt) * s.shear_I2) * inv_Jt;
      P = {g * F[0] - b * F[3], g * F[1] + b * F[2], g * F[2] + b * F[1], g * F[3] - b * F[0]};
      return StressStatus::ok;
    }
    const double g = s.shear, b = s.shear * s.c33 * inv_Jt; // Gbar c F~^{-T} = (Gbar c / J~) cof F~
    P              = {g * F[0] - b * F[3], g * F[1] + b * F[2], g * F[2] + b * F[1], g * F[3] - b * F[0]};
    return StressStatus::ok;
  }

  // lane_count bonds at once (T = Lanes; lanes.hpp: 8 with AVX-512, 4 with AVX2) or half
  // as many (T = HalfLanes: a point's last few bonds): F as lanes per component, c33 the warm starts
  // (<= 0: none). Runs the first one or two evaluations of solve() in every lane, with
  // the same arithmetic as solve() (so a lane's C33 and P are bit for bit those of
  // stress()), and returns the lanes where they end the solve (converged, or the step
  // accepted unevaluated: a warm-started time step's usual case). There P and c33
  // are written; every other lane (failure, locked point, a solve that needs more
  // evaluations) must go through stress(). Lanes may hold anything finite or not:
  // their arithmetic is kept finite (no floating-point trap) and they are not done.
  template <class T> MaskOf<T> stress_lanes(const std::array<T, 4> &F, T &c33, std::array<T, 4> &P) const
  {
    const T   one = T{} + 1.0, Jt = F[0] * F[3] - F[1] * F[2];
    const T   a0 = F[0] * F[0] + F[1] * F[1] + F[2] * F[2] + F[3] * F[3], k0 = Jt * Jt;
    MaskOf<T> ok = Jt > 0.0;
    if constexpr (Law::has_limit) {
      const double L = Law::I1bar_limit(p);
      ok &= 27.0 * a0 * a0 < 4.0 * k0 * L * L * L; // as solve(), with NaN on this side
    }
    // lanes that are not ok compute the rest state instead
    const T inv_Jt = 1.0 / select(ok, Jt, one), a = select(ok, a0, one + 1.0), k = select(ok, k0, one);
    const T inv_k  = inv_Jt * inv_Jt;
    T       lo, hi, c, s;
    start(a, k, inv_k, c33, lo, hi, c, s);
    const double                   inv_D = 1.0 / p.D;
    const PlaneStressResidualOf<T> r     = residual_at(a, k, inv_D, c, s);
    const PlaneStressStepOf<T>     st    = step(r, c, lo, hi);
    MaskOf<T>                      done  = ok & r.admissible & (st.converged | st.accepted);
    T                              root = st.c33, shear = st.shear, shear_I2 = st.shear_I2;
    const MaskOf<T>                more = ok & r.admissible & ~done;
    if (any(more)) {
      // A second evaluation, where solve() makes it at a Newton point (the larger time
      // steps): the same tests and arithmetic as its loop. Anything else (bisection, a
      // large step) is left to stress().
      const T   x = st.delta / c, next = c + st.delta;
      MaskOf<T> newton = more & (next > st.lo) & (next < st.hi) &
                         (2.0 * lane_abs(r.f[0]) <= lane_abs((hi - lo) * r.f[1])) & (lane_abs(st.delta) <= 0.1 * c);
      const T s_next = s * (1.0 + x * ((1.0 / 3.0) + x * ((-1.0 / 9.0) + x * (5.0 / 81.0))));
      const T c_next = s_next * s_next * s_next * inv_k;
      newton &= (c_next > st.lo) & (c_next < st.hi);
      if (any(newton)) {
        const T                        c2    = select(newton, c_next, c), s2 = select(newton, s_next, s);
        const PlaneStressResidualOf<T> r2    = residual_at(a, k, inv_D, c2, s2);
        const PlaneStressStepOf<T>     st2   = step(r2, c2, st.lo, st.hi);
        const MaskOf<T>                done2 = newton & r2.admissible & (st2.converged | st2.accepted);
        root                                     = select(done2, st2.c33, root);
        shear                                    = select(done2, st2.shear, shear);
        if constexpr (Law::uses_I2bar) shear_I2 = select(done2, st2.shear_I2, shear_I2);
        done |= done2;
      }
    }
    c33 = select(done, root, c33);
    if constexpr (Law::uses_I2bar) { // as stress()
      const T g = shear + root * shear_I2, b = (root * shear + (a * root - k) * shear_I2) * inv_Jt;
      P = {g * F[0] - b * F[3], g * F[1] + b * F[2], g * F[2] + b * F[1], g * F[3] - b * F[0]};
      return done;
    }
    const T b = shear * root * inv_Jt;
    P = {shear * F[0] - b * F[3], shear * F[1] + b * F[2], shear * F[2] + b * F[1], shear * F[3] - b * F[0]};
    return done;
  }

  // The exact tangent A[4 (2i + j) + (2k + l)] = dP~_ij / dF~_kl of a law of I1bar only
  // (has_tangent; the static solver's Hessian, ba_tangent.hpp), C33 solved as stress()
  // does. P~ = Gbar (F~ - c F~^{-T}) with Gbar(a, k, c) = G(I1bar) q, q = (c k)^{-1/3},
  // I1bar = (a + c) q, a = tr C~, k = J~^2, and c = C33(a, k) the root of f (eq 33), so
  // by implicit differentiation dc = -(f_a da + f_k dk) / f_c with da = 2 F~ : dF~ and
  // dk = 2 k F~^{-T} : dF~. Then with dGbar = Cg : dF~ and d(Gbar c) = Cb : dF~,
  //   A_ijkl = Gbar d_ik d_jl + F~_ij Cg_kl - F~^{-T}_ij Cb_kl + Gbar c F~^{-T}_il F~^{-T}_kj.
  static constexpr bool has_tangent = Law::variables == LawVariables::invariants && !Law::uses_I2bar;
  StressStatus tangent(const Mat2 &F, double c33, std::array<double, 16> &A) const
  {
    static_assert(has_tangent, "PlaneStress::tangent: a law of I1bar only (a law of I2bar takes differences of P)");
    const double              Jt = det(F), inv_Jt = Jt > 0.0 ? 1.0 / Jt : 0.0;
    const PlaneStressSolution s = solve(F, Jt, inv_Jt, c33);
    if (s.status != StressStatus::ok) return s.status;
    const double a = F[0] * F[0] + F[1] * F[1] + F[2] * F[2] + F[3] * F[3], k = Jt * Jt, c = s.c33;
    const double q = 1.0 / std::cbrt(c * k), I1bar = (a + c) * q, inv_D = 1.0 / p.D;
    ModulusOf<double> G;
    Law::modulus(p, InvariantsOf<double>{I1bar}, G);
    const double Gbar = s.shear, dG = G[1] * q; // Gbar as stress() has it; dG = q dG/dI1bar
    // partial derivatives of Gbar(a, k, c) (q_c = -q / 3c, q_k = -q / 3k)
    const double Gbar_a = dG * q;
    const double Gbar_c = dG * q * (1.0 - (a + c) / (3.0 * c)) - G[0] * q / (3.0 * c);
    const double Gbar_k = -dG * (a + c) * q / (3.0 * k) - G[0] * q / (3.0 * k);
    // f = Gbar t + (c k - 1)/D, t = (2c - a)/3
    const double t = (2.0 * c - a) / 3.0;
    const double f_c = Gbar_c * t + (2.0 / 3.0) * Gbar + k * inv_D;
    const double f_a = Gbar_a * t - Gbar / 3.0, f_k = Gbar_k * t + c * inv_D;
    const Mat2   FinvT = {F[3] * inv_Jt, -F[2] * inv_Jt, -F[1] * inv_Jt, F[0] * inv_Jt}; // cof F~ / J~
    Mat2         Cc, Cg, Cb;
    for (int kl = 0; kl < 4; ++kl) {
      const double da = 2.0 * F[kl], dk = 2.0 * k * FinvT[kl];
      Cc[kl]          = -(f_a * da + f_k * dk) / f_c;
      Cg[kl]          = Gbar_a * da + Gbar_k * dk + Gbar_c * Cc[kl];
      Cb[kl]          = c * Cg[kl] + Gbar * Cc[kl];
    }
    const double Gc = Gbar * c;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        for (int kk = 0; kk < 2; ++kk)
          for (int l = 0; l < 2; ++l) {
            const int ij = 2 * i + j, kl = 2 * kk + l;
            A[4 * ij + kl] = (i == kk && j == l ? Gbar : 0.0) + F[ij] * Cg[kl] - FinvT[ij] * Cb[kl] + Gc * FinvT[2 * i + l] * FinvT[2 * kk + j];
          }
    return StressStatus::ok;
  }

  // The reduced energy Psi(F~, C33(F~)) per unit reference volume.
  StressStatus energy(const Mat2 &F, double &c33, double &psi) const
  {
    const PlaneStressSolution s = solve(F, c33);
    if (s.status != StressStatus::ok) return s.status;
    c33            = s.c33;
    const double a = F[0] * F[0] + F[1] * F[1] + F[2] * F[2] + F[3] * F[3];
    const double J = std::sqrt(s.c33) * det(F);
    double       psi_iso;
    Invariants   inv{(a + s.c33) / std::cbrt(J * J)};
    if constexpr (Law::uses_I2bar) inv.I2bar = (det(F) * det(F) + a * s.c33) / std::cbrt(J * J * J * J); // (k + a c) J^{-4/3}
    if (!Law::energy(p, inv, psi_iso)) return StressStatus::chain_limit;
    psi = psi_iso + volumetric_energy_times_D(J) / p.D;
    return StressStatus::ok;
  }

private:
  // d^n (M(X(c)) y(c)) / dc^n, n = 0..4: M's X-derivatives M[n] composed with X's
  // c-derivatives X[0..3] = X', ..., X'''' (Faa di Bruno), times y with its derivatives
  // y[0..4] (Leibniz). dM_dc: M' X', how fast the modulus itself moves with c.
  // (Gbar = G(I1bar) q and Hbar = H(I2bar) q^2.)
  template <class T>
  static std::array<T, 5> modulus_times_power(const ModulusOf<T> &M, const std::array<T, 4> &X, const std::array<T, 5> &y, T &dM_dc)
  {
    const T X1 = X[0], X2 = X[1], X3 = X[2], X4 = X[3];
    const T H0 = M[0], H1 = M[1] * X1, H2 = M[2] * X1 * X1 + M[1] * X2;
    const T H3 = M[3] * X1 * X1 * X1 + 3.0 * M[2] * X1 * X2 + M[1] * X3;
    const T H4 = M[4] * (X1 * X1) * (X1 * X1) + 6.0 * M[3] * X1 * X1 * X2 + M[2] * (3.0 * X2 * X2 + 4.0 * X1 * X3) + M[1] * X4;
    dM_dc      = H1;
    return {H0 * y[0], H1 * y[0] + H0 * y[1], H2 * y[0] + 2.0 * H1 * y[1] + H0 * y[2],
            H3 * y[0] + 3.0 * H2 * y[1] + 3.0 * H1 * y[2] + H0 * y[3],
            H4 * y[0] + 4.0 * H3 * y[1] + 6.0 * H2 * y[2] + 4.0 * H1 * y[3] + H0 * y[4]};
  }

  // The bracket [lo, hi] of the root and the first iterate (c, s), c = s^3 / k: the warm
  // start where it lies in the bracket, else c = 1/k, s = 1 (see above).
  template <class T> static void start(T a, T k, T inv_k, T c33_guess, T &lo, T &hi, T &c, T &s)
  {
    const T c_iso = 0.5 * a;
    lo            = select(inv_k < c_iso, inv_k, c_iso); // std::min, std::max
    hi            = select(c_iso < inv_k, inv_k, c_iso);
    if constexpr (Law::uses_I2bar) { // the I2bar term's zero, 2k/a <= a/2
      const T c_I2 = 2.0 * k / a;
      lo           = select(c_I2 < lo, c_I2, lo);
    }
    const auto in_bracket = (c33_guess >= lo) & (c33_guess <= hi);
    const T    s_guess    = approximate_cbrt(select(in_bracket, c33_guess, inv_k) * k); // (no overflow)
    const T    c_guess    = s_guess * s_guess * s_guess * inv_k;
    const auto use        = in_bracket & (c_guess >= lo) & (c_guess <= hi);
    c                     = select(use, c_guess, inv_k);
    s                     = select(use, s_guess, T{} + 1.0);
  }

  // The stopping tests and the corrected Newton step at an admissible point (see above).
  template <class T> PlaneStressStepOf<T> step(const PlaneStressResidualOf<T> &r, T c, T lo, T hi) const
  {
    constexpr double     eps = std::numeric_limits<double>::epsilon();
    PlaneStressStepOf<T> st;
    const T              tol = 1e-13 * r.scale + 1e-12 * p.mu * c + 4.0 * eps * r.f[1] * c;
    st.converged             = (lane_abs(r.f[0]) <= tol) | (hi - lo <= 4.0 * eps * hi);
    const auto below         = r.f[0] < 0.0;
    st.lo                    = select(below, c, lo);
    st.hi                    = select(below, hi, c);
    const T inv_df = 1.0 / select(r.admissible, r.f[1], T{} + 1.0); // f' > 0 where admissible
    const T h      = -r.f[0] * inv_df;                               // Newton
    const T A2 = 0.5 * r.f[2] * inv_df, A3 = (1.0 / 6.0) * r.f[3] * inv_df;
    const T A4 = (1.0 / 24.0) * r.f[4] * inv_df, bend = A2 * h;
    st.delta   = select(lane_abs(bend) <= 0.1, h * (1.0 - bend + (2.0 * A2 * A2 - A3) * h * h),
                        select(lane_abs(bend) <= 0.5, h * (1.0 - bend), h));
    const T    next  = c + st.delta;
    auto small = (next > st.lo) & (next < st.hi) & (lane_abs(st.delta) <= 1e-3 * c) &
                 (lane_abs(st.delta) * r.dG_dc <= 1e-3 * r.G);
    if constexpr (Law::uses_I2bar) small &= lane_abs(st.delta) * r.dH_dc <= 1e-3 * r.H; // H's series too
    const T hs = select(small, h, T{}), h2 = hs * hs; // (large h: no overflow)
    const T left =
        lane_abs(r.f[1]) * h2 * h2 * (5.0 * lane_abs(A2) * (A2 * A2 + lane_abs(A3)) + lane_abs(A4));
    st.accepted = small & (left <= 0.5 * tol); // |f| <= tol at c + delta (see above)
    const T d   = st.delta;
    const T taken =
        r.shear[0] +
        d * (r.shear[1] + d * ((1.0 / 2.0) * r.shear[2] + d * ((1.0 / 6.0) * r.shear[3] + d * (1.0 / 24.0) * r.shear[4])));
    st.c33   = select(st.converged, c, next);
    st.shear = select(st.converged, r.shear[0], taken);
    if constexpr (Law::uses_I2bar) {
      const T taken_I2 =
          r.shear_I2[0] + d * (r.shear_I2[1] + d * ((1.0 / 2.0) * r.shear_I2[2] +
                                                    d * ((1.0 / 6.0) * r.shear_I2[3] + d * (1.0 / 24.0) * r.shear_I2[4])));
      st.shear_I2 = select(st.converged, r.shear_I2[0], taken_I2);
    }
    return st;
  }

  // Jt = det F~ and its inverse, shared with stress() so that it divides once.
  PlaneStressSolution solve(const Mat2 &F, double Jt, double inv_Jt, double c33_guess) const
  {
    PlaneStressSolution out;
    if (!(Jt > 0.0)) {
      out.status = StressStatus::inverted;
      return out;
    }
    const double a = F[0] * F[0] + F[1] * F[1] + F[2] * F[2] + F[3] * F[3]; // tr C~
    const double k = Jt * Jt, inv_k = inv_Jt * inv_Jt;
    if constexpr (Law::has_limit) {
      // least I1bar = 3 r^{2/3}, r = a/(2 J~) >= 1; beyond the limit L iff 27 r^2 >= L^3
      const double L = Law::I1bar_limit(p);
      if (!(27.0 * a * a < 4.0 * k * L * L * L)) {
        out.status = StressStatus::chain_limit;
        return out;
      }
    }
    const double inv_D = 1.0 / p.D, c_iso = 0.5 * a;
    double       lo, hi, c, s;
    start(a, k, inv_k, c33_guess, lo, hi, c, s);

    constexpr double eps    = std::numeric_limits<double>::epsilon();
    auto             middle = [](double l, double h) { return h > 4.0 * l ? std::sqrt(l * h) : 0.5 * (l + h); };
    double           step_before_last = hi - lo, last_step = hi - lo;
    for (int it = 1; it <= max_iterations; ++it) {
      const PlaneStressResidual r = residual_at(a, k, inv_D, c, s);
      out.evaluations             = it;
      double next;
      if (!r.admissible) {
        // locked: f = -inf left of the least-I1bar point a/2, +inf right of it
        if (c < c_iso) lo = c;
        else if (c > c_iso) hi = c;
        if (c == c_iso || hi - lo <= 4.0 * eps * hi) {
          out.status = StressStatus::chain_limit; // the finite set is below round-off
          return out;
        }
        next = middle(lo, hi);
      } else {
        const PlaneStressStepOf<double> st = step(r, c, lo, hi);
        if (st.converged || st.accepted) {
          out.c33      = st.c33;
          out.shear    = st.shear;
          out.shear_I2 = st.shear_I2;
          return out;
        }
        lo = st.lo, hi = st.hi;
        next              = c + st.delta;
        const bool inside = next > lo && next < hi;
        if (!inside || 2.0 * std::abs(r.f[0]) > std::abs(step_before_last * r.f[1])) next = middle(lo, hi);
        else if (std::abs(st.delta) <= 0.1 * c) {
          // s at the Newton point: (1 + x)^{1/3} = 1 + x/3 - x^2/9 + 5x^3/81 - ..., x = delta/c,
          // and c moved to s^3 / k, by O(x^4) <= 4e-6 of c: below the error the step
          // itself leaves, so the iteration keeps its order. Outside the bracket: bisect.
          const double x      = st.delta / c;
          const double s_next = s * (1.0 + x * ((1.0 / 3.0) + x * ((-1.0 / 9.0) + x * (5.0 / 81.0))));
          const double c_next = s_next * s_next * s_next * inv_k;
          if (c_next > lo && c_next < hi) {
            step_before_last = last_step;
            last_step        = std::abs(c_next - c);
            c                = c_next;
            s                = s_next;
            continue;
          }
          next = middle(lo, hi);
        }
      }
      // a bisection, a large Newton step or a locked point: s from libm's cbrt (rare)
      step_before_last = last_step;
      last_step        = std::abs(next - c);
      c                = next;
      s                = std::cbrt(c * k);
    }
    out.status = StressStatus::no_convergence;
    return out;
  }
};

} // namespace bapd
