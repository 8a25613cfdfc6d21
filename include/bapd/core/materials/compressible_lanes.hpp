#pragma once
// The compressible 3D law (hyperelastic.hpp, Compressible3D: paper eqs 24, 26) with a
// lane path for the 3D bond kernel: P(F) of lane_count bonds at a time (lanes.hpp: 8
// with AVX-512, else 4), as PlaneStress has in 2D. In the scalar Compressible3D, libm's
// cbrt for J^{-2/3} is the largest single cost of a 3D bond; here
//   J^{-2/3} = z = (J^2)^{-1/3}: approximate_cbrt (4e-7) inverted, then two
//   division-free Newton steps z <- z (4 - J^2 z^3) / 3 (quadratic: 4e-7 -> 3e-13 ->
//   round-off),
// and P = G J^{-2/3} F + ((J^2 - 1)/D - G J^{-2/3} tr C / 3) cof(F) / J (eq 26) for
// every lane at once. A lane whose F is inverted (J <= 0) or past the law's limit is
// not done: the kernel hands it to the scalar stress(), which reports the failure.
// The lane result differs from the scalar one by round-off only (the cube root), and
// which path a bond takes depends on its own F alone, so the forces are the same on
// any rank layout. Laws of I1bar alone (Mooney-Rivlin's I2bar term is not written
// here: has_lanes is false for it, and the kernel then calls stress() bond by bond).
#include <array>

#include "bapd/core/materials/hyperelastic.hpp"
#include "bapd/core/materials/hyperelastic_numerics.hpp"
#include "bapd/core/kernel/lanes.hpp"

namespace bapd::nd {

template <class Law> struct Compressible3DLanes : Compressible3D<Law> {
  static constexpr bool has_lanes = !Law::uses_I2bar;

  Compressible3DLanes() = default;
  explicit Compressible3DLanes(const ParametersOf<Law> &p) : Compressible3D<Law>{p} {}

  // The scalar path (failures, and the kernel's fallback): Compressible3D's, with the
  // c33 argument of the lane interface (unused in 3D).
  using Compressible3D<Law>::stress;
  StressStatus stress(const Mat3 &F, double &, Mat3 &P) const { return Compressible3D<Law>::stress(F, P); }
  using Compressible3D<Law>::energy;

  // Done lanes get P; the others are left to stress(). c33: unused (the lane interface).
  LaneMask stress_lanes(const std::array<Lanes, 9> &F, Lanes &, std::array<Lanes, 9> &P) const
  {
    const auto &p = this->p;
    // cof(F) = J F^{-T}
    const Lanes c0 = F[4] * F[8] - F[5] * F[7], c1 = F[5] * F[6] - F[3] * F[8], c2 = F[3] * F[7] - F[4] * F[6];
    const Lanes J  = F[0] * c0 + F[1] * c1 + F[2] * c2;
    LaneMask    ok = J > 0.0;
    const Lanes Js = select(ok, J, Lanes{} + 1.0), J2 = Js * Js;
    Lanes       trC = F[0] * F[0];
    for (int k = 1; k < 9; ++k) trC = trC + F[k] * F[k];
    Lanes q = 1.0 / approximate_cbrt(J2); // J^{-2/3} = (J^2)^{-1/3} to 4e-7
    for (int it = 0; it < 2; ++it) q = q * (4.0 - J2 * q * q * q) * (1.0 / 3.0);
    ModulusOf<Lanes> G;
    ok = ok & Law::modulus(p, InvariantsOf<Lanes>{trC * q, Lanes{}}, G);
    const Lanes a = G[0] * q;
    const Lanes b = ((J2 - 1.0) / p.D - a * trC / 3.0) / Js; // times cof(F) = J F^{-T}
    const Lanes cof[9] = {c0,
                          c1,
                          c2,
                          F[2] * F[7] - F[1] * F[8],
                          F[0] * F[8] - F[2] * F[6],
                          F[1] * F[6] - F[0] * F[7],
                          F[1] * F[5] - F[2] * F[4],
                          F[2] * F[3] - F[0] * F[5],
                          F[0] * F[4] - F[1] * F[3]};
    for (int k = 0; k < 9; ++k) P[k] = a * F[k] + b * cof[k];
    return ok;
  }
};

} // namespace bapd::nd
