#pragma once
// -failure_softening: how a bond fails under the fracture-energy criterion
// (softening.hpp; docs/method.md section 5.4).
namespace bapd {

enum class Softening { none, linear, exponential };

inline const char *to_string(Softening s)
{
  switch (s) {
  case Softening::none: return "none";
  case Softening::linear: return "linear";
  case Softening::exponential: return "exponential";
  }
  return "?";
}

} // namespace bapd
