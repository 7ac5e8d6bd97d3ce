#pragma once
// The one guard every stepper puts around the system it integrates (make_stepper does it): a
// non-finite or non-physical state (density <= 0, internal energy < 0) and a non-finite
// derivative or stiff diagonal are recoverable failures (the stepper retries with a smaller
// step, see integrate/stepper.hpp), and the message names the particles concerned. Optionally
// it injects a NaN from a given time on (StepperOptions::inject_nan_from, a testing aid for the
// blow-up path: retries, then a clean failure with the last good state).
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "sphark/integrate/ode_system.hpp"
#include "sphark/state/state_layout.hpp"

namespace sphark {

// "<field> of particles 3, 17, 42 (+5 more)" for the state entries `entries` (ascending), or ""
// when empty (fields of a species other than the first are named "<species> <field>"). At most
// `max_named` particles are named per field.
std::string describe_entries(const StateLayout& layout, const std::vector<std::size_t>& entries,
                             std::size_t max_named = 5);

// Entries of y that are non-finite, or non-physical: a density that is not positive, a negative
// internal energy (for the fields the layout has, in every species); ascending. (Smoothing
// lengths are not in y: a scheme that solves h in its RHS reports a failed or runaway h
// iteration itself, as a recoverable failure.)
std::vector<std::size_t> nonphysical_entries(const StateLayout& layout, const Real* y);

class GuardedSystem final : public OdeSystem {
 public:
  // The checks use inner.state_layout(); a system without a layout is checked for finiteness.
  explicit GuardedSystem(OdeSystem& inner) : inner_(inner) {}

  // From time t on, rhs() puts a NaN into the velocity derivative of particle 0, or into the
  // first entry of the derivative if there is no velocity field (testing aid).
  void inject_nan_from(Real t) { inject_from_ = t; }

  std::size_t size() const override { return inner_.size(); }
  const StateLayout* state_layout() const override { return inner_.state_layout(); }
  int rhs(Real t, const Real* y, Real* ydot) override;
  bool has_stiff_diagonal() const override { return inner_.has_stiff_diagonal(); }
  int stiff_diagonal(Real t, const Real* y, Real* c) override;
  std::size_t position_offset() const override { return inner_.position_offset(); }
  std::size_t velocity_offset() const override { return inner_.velocity_offset(); }
  std::size_t position_size() const override { return inner_.position_size(); }
  Real max_stable_dt(Real t, const Real* y, const Real* ydot) override { return inner_.max_stable_dt(t, y, ydot); }
  int num_roots() const override { return inner_.num_roots(); }
  int roots(Real t, const Real* y, Real* g) override { return inner_.roots(t, y, g); }
  std::string last_error() const override { return own_error_ ? error_ : inner_.last_error(); }

  long guarded_failures() const { return failures_; }

 private:
  int fail(Real t, const std::string& what, const std::vector<std::size_t>& entries);
  int check(Real t, const Real* out, std::size_t n, const char* what);

  OdeSystem& inner_;
  Real inject_from_ = std::numeric_limits<Real>::infinity();
  bool own_error_ = false;
  std::string error_;
  long failures_ = 0;
};

}  // namespace sphark
