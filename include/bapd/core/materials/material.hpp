#pragma once
// Constitutive models behind one small interface (docs/method.md section 4).
//
// Every model that the 2D bond kernel can use provides
//   StressStatus stress(const Mat2 &F, double &c33, Mat2 &P) const;
//   StressStatus energy(const Mat2 &F, double &c33, double &psi) const;
// F is the in-plane deformation gradient F~, P the in-plane first Piola-Kirchhoff
// stress P~. c33 = C33 = lambda_3^2 is the out-of-plane state: plane-stress models
// read it as a warm start (<= 0 means "none") and write the solved value back only
// when the status is ok (a failed call leaves the warm start alone); plane-strain
// models set it to 1. P is zeroed and psi left alone unless the status is ok. Models
// are picked at run time once, outside the hot loops (with_model in bapd/models.hpp),
// and are concrete types inside them. A model may also provide, with
// `static constexpr bool has_lanes = true`,
//   LaneMask stress_lanes(const std::array<Lanes, 4> &F, Lanes &c33, std::array<Lanes, 4> &P) const;
// lane_count bonds at a time (lanes.hpp), giving bit for bit what stress() gives in the lanes
// it reports done; the bond kernel (ba_force.hpp) then uses it (PlaneStress does, as a
// template over the register that also takes HalfLanes: a point's last few bonds).
//
// A model is a formulation of a law. Where the files are:
//   bapd/law.hpp            what a law is (on I1bar, I2bar; the shared U(J)), and
//                           what a formulation may refuse
//   bapd/gent.hpp           the Gent law (paper eq 24) and its aliases
//   bapd/neo_hookean.hpp    the neo-Hookean law and its aliases
//   bapd/mooney_rivlin.hpp, yeoh.hpp, arruda_boyce.hpp, ogden.hpp  the other laws
//                           (docs/laws.md); inverse_langevin.hpp for Arruda-Boyce
//   bapd/homogeneous_response.hpp  their incompressible test responses (bapd-fit)
//   bapd/law_list.hpp       the list of laws (ModelKind, Formulation)
//   bapd/material_parameters.hpp  MaterialParameters: mu, D and every law's values
//   bapd/law_registry.hpp   the laws' types and run-time entries, from the list
//   bapd/hyperelastic.hpp   Compressible3D, PlaneStrain
//   bapd/plane_stress.hpp   PlaneStress (the S33 = 0 solve) and what it requires
//   bapd/hyperelastic_numerics.hpp, bapd/numerical_tangent.hpp  their helpers
//   bapd/models.hpp         with_model: ModelKind x Formulation -> concrete model
//
// The Gent chain-extension limit. Gent has no finite energy once I1bar - 3 >= Jm;
// a model evaluated there returns StressStatus::chain_limit and writes no stress.
// The bond kernel then breaks the bond when failure is enabled; otherwise the run
// stops with a message naming the law's limit, and the diagnosis names the option that
// moves it (LawEntry::limit, limit_option: -material_Jm; Arruda-Boyce's
// -material_lambda_m).
// In plane stress with a finite D the limit is reached only when even the least
// I1bar over all thickness stretches, 3 (trC~ / (2 J~))^{2/3}, is beyond it: short
// of that the sheet thickens (J > 1) and the stress rises on the bulk-modulus scale
// K = 2/D instead (see PlaneStress in plane_stress.hpp).
#include <string>

#include "bapd/core/materials/law_list.hpp"
#include "bapd/core/materials/material_parameters.hpp"
#include "bapd/core/materials/stress_status.hpp"

namespace bapd {

// Names as written in options (-material_model gent|neo_hookean, from the registry;
// -material_formulation plane_stress|plane_strain).
const char *to_string(ModelKind k);
const char *to_string(Formulation f);
// false (and the output untouched) for an unknown name.
bool parse(const std::string &name, ModelKind &k);
bool parse(const std::string &name, Formulation &f);

// Empty when the parameters are usable by the model; otherwise one message per bad
// value, naming the option (-material_mu, the law's own such as -material_Jm,
// -material_D) and the fix.
std::string check_parameters(ModelKind k, const MaterialParameters &p);
// check_parameters, and then whether the law runs in formulation f (law.hpp:
// formulation_refusal): empty when the model can be built.
std::string check_model(ModelKind k, Formulation f, const MaterialParameters &p);
// The law's own parameters for the scene summary (law.hpp: law_summary), ", Jm 162.6";
// empty for a law with none.
std::string parameter_summary(ModelKind k, const MaterialParameters &p);

} // namespace bapd
