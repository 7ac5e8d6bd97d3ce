#pragma once
// The contract between a physics scheme and every time stepper (ARKODE ERK, ARKODE IMEX,
// leapfrog). A scheme sees only raw arrays laid out by its StateLayout; it never sees SUNDIALS.
//
// Return codes of rhs()/stiff_diagonal()/roots(): 0 success, > 0 recoverable (the stepper
// retries with a smaller step), < 0 fatal. Implementations should catch their own exceptions
// and return -1 with last_error() set; the steppers also catch anything that escapes (never
// letting it cross into SUNDIALS) and report it as a fatal failure.
#include <cstddef>
#include <limits>
#include <string>

#include "sphark/core/types.hpp"

namespace sphark {

class OdeSystem {
 public:
  virtual ~OdeSystem() = default;

  // Length of the state vector.
  virtual std::size_t size() const = 0;

  // Full right-hand side ydot = f(t, y).
  virtual int rhs(Real t, const Real* y, Real* ydot) = 0;

  // IMEX split: the stiff part is diagonal and linear, f_I(y)_k = -c_k y_k with c_k >= 0 (e.g.
  // psi damping -psi/tau). f_E = f - f_I. Systems without a stiff part return false.
  virtual bool has_stiff_diagonal() const { return false; }
  virtual int stiff_diagonal(Real /*t*/, const Real* /*y*/, Real* /*c*/) { return -1; }

  // Leapfrog (kick-drift-kick) needs to know which block is position and which is velocity:
  // x = y[position_offset() .. + position_size()), v = y[velocity_offset() .. + position_size()).
  // Every other entry is "kicked" like the velocity.
  virtual std::size_t position_offset() const { return 0; }
  virtual std::size_t velocity_offset() const { return 0; }
  virtual std::size_t position_size() const { return 0; }

  // Largest stable step for the current state (CFL, force and any other criteria), used by the
  // leapfrog stepper and as an upper bound hint. +inf when the system has no such limit.
  virtual Real max_stable_dt(Real /*t*/, const Real* /*y*/) { return std::numeric_limits<Real>::infinity(); }

  // Event (root) functions g_k(t, y); a sign change stops the integration at the root.
  virtual int num_roots() const { return 0; }
  virtual int roots(Real /*t*/, const Real* /*y*/, Real* /*g*/) { return 0; }

  // Human-readable reason of the last non-zero return (for the run summary).
  virtual std::string last_error() const { return {}; }
};

}  // namespace sphark
