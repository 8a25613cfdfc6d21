#pragma once
// The run-time choice of constitutive model, made once outside the hot loops:
//
//   with_model(scene.material.model, scene.material.formulation, scene.material.parameters, [&](const auto &model) {
//     ... loop over bonds calling model.stress(F, c33, P) ...
//   });
//
// The lambda is instantiated once per concrete model (every registered law,
// law_registry.hpp, in every formulation that accepts it), so inside it every call is
// inline. Every branch must return the same type. A formulation that refuses the law
// (formulation_refusal, law.hpp) is never instantiated for it: choosing it throws
// std::invalid_argument with the refusal, which check_model reports up front.
#include <cstddef>
#include <stdexcept>

#include "bapd/core/materials/hyperelastic.hpp"
#include "bapd/core/materials/law_registry.hpp"
#include "bapd/core/materials/material.hpp"
#include "bapd/core/materials/compressible_lanes.hpp"
#include "bapd/core/materials/plane_stress.hpp"
#include "bapd/core/materials/plane_stress_incompressible.hpp"

namespace bapd {

namespace detail {
template <std::size_t I, class Fn>
decltype(auto) with_law(ModelKind kind, Formulation formulation, const MaterialParameters &p, Fn &fn)
{
  using Law = std::tuple_element_t<I, RegisteredLaws>;
  if constexpr (I + 1 < registered_law_count)
    if (kind != static_cast<ModelKind>(I)) return with_law<I + 1>(kind, formulation, p, fn);
  if constexpr (has_own_formulations<Law>) { // a law of principal stretches (law.hpp)
    if (formulation == Formulation::plane_stress) return fn(typename Law::PlaneStressModel{p});
    if (formulation != Formulation::plane_strain) throw std::invalid_argument(formulation_refusal<Law>(formulation));
    return fn(typename Law::PlaneStrainModel{p});
  } else {
    if (formulation == Formulation::plane_stress_incompressible) return fn(PlaneStressIncompressible<Law>{p});
    if constexpr (accepts_plane_stress<Law>)
      if (formulation == Formulation::plane_stress) return fn(PlaneStress<Law>{p});
    if (formulation != Formulation::plane_strain) throw std::invalid_argument(formulation_refusal<Law>(formulation));
    return fn(PlaneStrain<Law>{p});
  }
}

// The 3D form of law I (with_model_3d): a law of invariants as Compressible3DLanes; a
// law of principal stretches (Ogden) as its own scalar 3D model, Law::Model3D (no lane
// path: the kernel calls its stress() bond by bond).
template <std::size_t I, class Fn> void with_law_3d(ModelKind kind, const MaterialParameters &p, Fn &fn)
{
  using Law = std::tuple_element_t<I, RegisteredLaws>;
  if constexpr (I + 1 < registered_law_count)
    if (kind != static_cast<ModelKind>(I)) return with_law_3d<I + 1>(kind, p, fn);
  if constexpr (has_own_formulations<Law>) fn(typename Law::Model3D{p});
  else fn(nd::Compressible3DLanes<Law>{p});
}
} // namespace detail

// The 3D dispatch (a 3D body, BodySection::dimension 3): fn(model) with the law's 3D form,
// nd::Compressible3DLanes<Law> (stress(F, P), the lane path of ba_force.hpp), for
// every law of invariants of the registry, Law::Model3D for a law of principal
// stretches (Ogden3D). fn returns nothing.
template <class Fn> void with_model_3d(ModelKind kind, const MaterialParameters &p, Fn &&fn)
{
  detail::with_law_3d<0>(kind, p, fn);
}

template <class Fn>
decltype(auto) with_model(ModelKind kind, Formulation formulation, const MaterialParameters &p, Fn &&fn)
{
  return detail::with_law<0>(kind, formulation, p, fn);
}

} // namespace bapd
