// Names, messages and parameter checks for the constitutive models (material.hpp).
#include "bapd/core/materials/material.hpp"

#include "bapd/core/enum_words.hpp"
#include "bapd/core/materials/law_registry.hpp"

#include <cmath>
#include <sstream>

namespace bapd {

namespace {
constexpr EnumWords<StressStatus::no_convergence> stress_status_words{"ok", "chain_limit", "inverted", "no_convergence"};
} // namespace

const char *to_string(StressStatus s) { return stress_status_words(s); }

const char *describe(StressStatus s)
{
  switch (s) {
  case StressStatus::ok: return "the stress was evaluated";
  case StressStatus::chain_limit:
    return "a bond reached its law's limit (the Gent chain limit I1bar - 3 >= Jm, or the Arruda-Boyce locking "
           "stretch I1bar >= 3 lambda_m^2), where the model has no finite energy: raise -material_Jm or "
           "-material_lambda_m, lower the load, or enable failure (-failure_critical_stretch) so that such bonds "
           "break (a run names its law's own: simulation_health.cpp)";
  case StressStatus::inverted:
    return "a bond deformation gradient has det F <= 0 (the material is inverted): the run is unstable; "
           "lower -time_step or -time_step_safety";
  case StressStatus::no_convergence:
    return "the plane-stress solve for C33 (S33 = 0) did not converge: check -material_D (> 0, not "
           "vanishingly small) and that the deformation is finite";
  }
  return "unknown stress status";
}

const char *to_string(ModelKind k) { return law_entry(k).name; }
const char *to_string(Formulation f)
{
  switch (f) {
  case Formulation::plane_stress: return "plane_stress";
  case Formulation::plane_strain: return "plane_strain";
  case Formulation::plane_stress_incompressible: return "plane_stress_incompressible";
  }
  return "unknown formulation";
}

bool parse(const std::string &name, ModelKind &k)
{
  for (const LawEntry &law : registered_laws())
    if (name == law.name) {
      k = law.kind;
      return true;
    }
  return false;
}

bool parse(const std::string &name, Formulation &f)
{
  if (name == "plane_stress") f = Formulation::plane_stress;
  else if (name == "plane_strain") f = Formulation::plane_strain;
  else if (name == "plane_stress_incompressible") f = Formulation::plane_stress_incompressible;
  else return false;
  return true;
}

// mu and D, which every law has, around the law's own checks (in option order).
std::string check_parameters(ModelKind k, const MaterialParameters &p)
{
  std::ostringstream msg;
  if (!(p.mu > 0.0) || !std::isfinite(p.mu))
    msg << "-material_mu " << p.mu << ": the shear modulus must be a positive number of Pa (paper: 4.55e3)\n";
  msg << law_entry(k).check(p);
  if (!(p.D > 0.0) || !std::isfinite(p.D)) {
    msg << "-material_D " << p.D << ": the compressibility must be > 0 (bulk modulus K = 2/D); e.g. ";
    if (p.mu > 0.0) msg << "-material_D " << 2.0 / (100.0 * p.mu) << " for K = 100 mu\n";
    else msg << "K = 100 mu\n";
  }
  return msg.str();
}

std::string check_model(ModelKind k, Formulation f, const MaterialParameters &p)
{
  std::string problems = check_parameters(k, p);
  const std::string refusal = law_entry(k).refusal(f);
  if (!refusal.empty()) problems += refusal + "\n";
  return problems;
}

std::string parameter_summary(ModelKind k, const MaterialParameters &p) { return law_entry(k).summary(p); }

} // namespace bapd
