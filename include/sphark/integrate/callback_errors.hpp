#pragma once
// Error reporting of the noexcept OdeSystem callbacks (rhs, prepare, ...): no exception may cross
// a SUNDIALS C callback, so every callback catches and returns a code (integrate/ode_system.hpp:
// 0 ok, > 0 recoverable, < 0 fatal) with a message for last_error().
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

// 0 if ydot[0..n) is finite; else 1 (recoverable: the stepper retries with a smaller step) and
// `error` names the first non-finite entry.
inline int check_finite_rhs(const Real* ydot, std::size_t n, std::string& error) noexcept {
  for (std::size_t k = 0; k < n; ++k)
    if (!std::isfinite(ydot[k])) {
      error = "non-finite right-hand side entry " + std::to_string(k);
      return 1;
    }
  return 0;
}

}  // namespace sphark
