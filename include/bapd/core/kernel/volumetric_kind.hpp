#pragma once
// -material_volumetric: where the volumetric energy U(J) is evaluated, per bond (the
// paper's) or once per point from the mean dilatation (volumetric.hpp says how;
// docs/method.md section 8). Apart from the kernel so that the scene names it without
// the kernel's numerics.

namespace bapd {

enum class Volumetric { bond, point };

// "bond", "point" (the -material_volumetric values).
inline const char *to_string(Volumetric v) { return v == Volumetric::point ? "point" : "bond"; }

} // namespace bapd
