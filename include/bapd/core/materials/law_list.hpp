#pragma once
// The one list of hyperelastic laws the user can pick with -material_model, and the
// two choices a scene holds (ModelKind, Formulation). This header includes nothing, so
// that a scene names its law without every law header; the law types themselves come
// together in law_registry.hpp, which generates everything else from this list.
//
// X(type, id): the law's struct (its header: bapd/core/materials/<id>.hpp, whose
// #include the build generates from this line: cmake/law_headers.cmake) and its
// -material_model name (static_asserted equal to type::name).
// One line per law; the order is the order of -help, docs and the tests. Every line
// ends in a backslash (the blank line after the list ends it), so that a new law is
// one added line.
#define BAPD_REGISTERED_LAWS(X)  \
  X(Gent, gent)                  \
  X(NeoHookean, neo_hookean)     \
  X(MooneyRivlin, mooney_rivlin) \
  X(Yeoh, yeoh)                  \
  X(ArrudaBoyce, arruda_boyce)   \
  X(Ogden, ogden)                \


namespace bapd {

// The law's id, ModelKind::<id>, in list order.
enum class ModelKind {
#define BAPD_LAW_ID(type, id) id,
  BAPD_REGISTERED_LAWS(BAPD_LAW_ID)
#undef BAPD_LAW_ID
};

// The 2D reduction of a law (a 3D body uses the law's full 3D form); the last is plane
// stress at J = 1 exactly (plane_stress_incompressible.hpp).
enum class Formulation { plane_stress, plane_strain, plane_stress_incompressible };

} // namespace bapd
