#pragma once
// -failure_softening: how a bond fails under the fracture-energy criterion
// (softening.hpp; docs/method.md section 5.4).
#include "bapd/core/enum_words.hpp"

namespace bapd {

enum class Softening { none, linear, exponential, time };
inline constexpr EnumWords<Softening::time> softening_words{"none", "linear", "exponential", "time"};

inline const char *to_string(Softening s) { return softening_words(s); }

} // namespace bapd
