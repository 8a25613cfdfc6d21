#pragma once
// Constitutive models behind one small interface (METHOD.md section 4).
//
// Every model that the 2D bond kernel can use provides
//   StressStatus stress(const Mat2 &F, double &c33, Mat2 &P) const;
//   StressStatus energy(const Mat2 &F, double &c33, double &psi) const;
// F is the in-plane deformation gradient F~, P the in-plane first Piola-Kirchhoff
// stress P~. c33 = C33 = lambda_3^2 is the out-of-plane state: plane-stress models
// read it as a warm start (<= 0 means "none") and write the solved value back;
// plane-strain models set it to 1. Models are picked at run time once, outside the
// hot loops (with_model below), and are concrete types inside them.
#include "bapd/tensor.hpp"

namespace bapd {

enum class StressStatus : int {
  ok             = 0,
  chain_limit    = 1, // I1bar - 3 >= Jm: the Gent model has no finite energy here
  inverted       = 2, // det F <= 0
  no_convergence = 3  // the plane-stress C33 solve did not converge
};
const char *to_string(StressStatus s);

enum class ModelKind { gent, neo_hookean };
enum class Formulation { plane_stress, plane_strain };

struct MaterialParameters {
  double mu = 4.55e3; // shear modulus [Pa]
  double Jm = 162.6;  // Gent chain-extension limit [-] (ignored by neo-Hookean)
  double D  = 0.0;    // compressibility [1/Pa]; bulk modulus at rest K = 2/D
};

} // namespace bapd
