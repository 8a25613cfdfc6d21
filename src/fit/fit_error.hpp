#pragma once
// The one error type of bapd-fit: main() prints "bapd-fit: error: <what>" and exits 1.
#include <stdexcept>
#include <string>

namespace bapd::fit {
struct FitError : std::runtime_error {
  explicit FitError(const std::string &what) : std::runtime_error(what) {}
};
} // namespace bapd::fit
