#pragma once
// The run-time choice of constitutive model, made once outside the hot loops:
//
//   with_model(scene.model, scene.formulation, scene.material, [&](const auto &model) {
//     ... loop over bonds calling model.stress(F, c33, P) ...
//   });
//
// The lambda is instantiated once per concrete model, so inside it every call is
// inline. Every branch must return the same type. A new law adds one header and one
// line here.
#include "bapd/gent.hpp"
#include "bapd/material.hpp"
#include "bapd/neo_hookean.hpp"

namespace bapd {

template <class Fn>
decltype(auto) with_model(ModelKind kind, Formulation formulation, const MaterialParameters &p, Fn &&fn)
{
  const bool plane_strain = formulation == Formulation::plane_strain;
  if (kind == ModelKind::neo_hookean) {
    if (plane_strain) return fn(NeoHookeanPlaneStrain{p});
    return fn(NeoHookeanPlaneStress{p});
  }
  if (plane_strain) return fn(GentPlaneStrain{p});
  return fn(GentPlaneStress{p});
}

} // namespace bapd
