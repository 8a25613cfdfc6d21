#pragma once
// Which bond force the kernel computes (-force_form; ba_force.hpp computes both):
// the paper's bond-only form (eq 23), or the energy-consistent one, minus the gradient
// of the strain energy (docs/method.md section 3), whose undamped motion conserves energy
// where the bond-only form's grows near free surfaces (flutter). One enum for the
// scene and the kernel, for every D.

#include "bapd/core/enum_words.hpp"

namespace bapd {

enum class ForceForm { bond_only, energy_consistent };
// "bond_only", "energy_consistent" (the -force_form values).
inline constexpr EnumWords<ForceForm::energy_consistent> force_form_words{"bond_only", "energy_consistent"};

inline const char *to_string(ForceForm form) { return force_form_words(form); }

} // namespace bapd
