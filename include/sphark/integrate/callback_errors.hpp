#pragma once
// The message of the exception being handled, for the places that turn exceptions into failure
// codes (the steppers at the C boundary, a scheme's diagnostics path): integrate/ode_system.hpp.
#include <cmath>
#include <cstddef>
#include <exception>
#include <string>

#include "sphark/core/types.hpp"

namespace sphark {

// Inside a catch block: "<who>: <what()>" of the exception being handled.
inline std::string current_exception_message(const std::string& who) noexcept {
  try {
    throw;
  } catch (const std::exception& e) {
    return who + ": " + e.what();
  } catch (...) {
    return who + ": unknown exception";
  }
}

}  // namespace sphark
