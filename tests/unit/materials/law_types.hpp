#pragma once
// The typed tests' lists, generated from the law registry (law_registry.hpp): a law
// added there is tested everywhere these are used, with nothing to add here.
//   LawTypes                 every registered law
//   InvariantLawTypes        the laws written in I1bar, I2bar (law.hpp: LawVariables)
//   InvariantPlaneStressModels  PlaneStress<Law> for those the plane-stress solve accepts
//   PlaneStressModels, PlaneStrainModels, Models3D  every law's model in each formulation
//                            (its own for a law of principal stretches: Ogden)
//   Models2D                 PlaneStressModels and PlaneStrainModels together
#include <gtest/gtest.h>

#include <tuple>
#include <type_traits>
#include <utility>

#include "bapd/core/materials/law_registry.hpp"

namespace bapd::test {

template <class Tuple> struct GTestTypesOf;
template <class... T> struct GTestTypesOf<std::tuple<T...>> {
  using type = ::testing::Types<T...>;
};
template <class Tuple> using GTestTypes = typename GTestTypesOf<Tuple>::type;

template <template <class> class Keep, class Tuple> struct FilterOf;
template <template <class> class Keep, class... L> struct FilterOf<Keep, std::tuple<L...>> {
  using type = decltype(std::tuple_cat(std::declval<std::conditional_t<Keep<L>::value, std::tuple<L>, std::tuple<>>>()...));
};
template <template <class> class F, class Tuple> struct MapOf;
template <template <class> class F, class... L> struct MapOf<F, std::tuple<L...>> {
  using type = std::tuple<typename F<L>::type...>;
};

template <class Law> struct IsInvariantLaw : std::bool_constant<Law::variables == LawVariables::invariants> {};
template <class Law> struct IsInvariantPlaneStressLaw : std::bool_constant<IsInvariantLaw<Law>::value && accepts_plane_stress<Law>> {};

// A law's model in each formulation, as with_model and with_model_3d pick it (models.hpp),
// but the scalar Compressible3D for a law of invariants (the lane form is the kernel's).
template <class Law, bool own = has_own_formulations<Law>> struct ModelsOf {
  using PlaneStress = bapd::PlaneStress<Law>;
  using PlaneStrain = bapd::PlaneStrain<Law>;
  using Solid       = Compressible3D<Law>;
};
template <class Law> struct ModelsOf<Law, true> {
  using PlaneStress = typename Law::PlaneStressModel;
  using PlaneStrain = typename Law::PlaneStrainModel;
  using Solid       = typename Law::Model3D;
};
template <class Law> struct PlaneStressModelOf {
  using type = typename ModelsOf<Law>::PlaneStress;
};
template <class Law> struct PlaneStrainModelOf {
  using type = typename ModelsOf<Law>::PlaneStrain;
};
template <class Law> struct Model3DOf {
  using type = typename ModelsOf<Law>::Solid;
};
template <class Law> struct InvariantPlaneStressOf {
  using type = bapd::PlaneStress<Law>;
};

using InvariantLaws = typename FilterOf<IsInvariantLaw, RegisteredLaws>::type;
using PlaneStressModelList = typename MapOf<PlaneStressModelOf, RegisteredLaws>::type;
using PlaneStrainModelList = typename MapOf<PlaneStrainModelOf, RegisteredLaws>::type;

using LawTypes                   = GTestTypes<RegisteredLaws>;
using InvariantLawTypes          = GTestTypes<InvariantLaws>;
using InvariantPlaneStressModels = GTestTypes<
    typename MapOf<InvariantPlaneStressOf, typename FilterOf<IsInvariantPlaneStressLaw, RegisteredLaws>::type>::type>;
using PlaneStressModels = GTestTypes<PlaneStressModelList>;
using PlaneStrainModels = GTestTypes<PlaneStrainModelList>;
using Models2D  = GTestTypes<decltype(std::tuple_cat(std::declval<PlaneStressModelList>(), std::declval<PlaneStrainModelList>()))>;
using Models3D  = GTestTypes<typename MapOf<Model3DOf, RegisteredLaws>::type>;

} // namespace bapd::test
