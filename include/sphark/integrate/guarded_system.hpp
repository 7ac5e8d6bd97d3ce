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

#include "sphark/integrate/forwarding_system.hpp"
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

class GuardedSystem final : public ForwardingSystem {
 public:
  // The checks use inner.state_layout(); a system without a layout is checked for finiteness.
  explicit GuardedSystem(OdeSystem& inner) : ForwardingSystem(inner) {}

  // From time t on, rhs() puts a NaN into the velocity derivative of particle 0, or into the
  // first entry of the derivative if there is no velocity field (testing aid).
  void inject_nan_from(Real t) { inject_from_ = t; }

  int rhs(Real t, const Real* y, Real* ydot) override;
  // Guarded like rhs(); counts active.size() particle evaluations.
  int rhs_subset(Real t, const Real* y, std::span<const std::size_t> active, Real* ydot) override;
  int stiff_diagonal(Real t, const Real* y, Real* c) override;
  std::string last_error() const override { return own_error_ ? error_ : inner_.last_error(); }

  long guarded_failures() const { return failures_; }
  // Particles whose derivatives the inner system was asked for: num_particles() per rhs(), the
  // active set's size per rhs_subset() (StepperStats::particle_evals; issue #17).
  long particle_evals() const { return particle_evals_; }

 private:
  int fail(Real t, const std::string& what, const std::vector<std::size_t>& entries);
  int check(Real t, const Real* out, std::size_t n, const char* what);
  int check_state(Real t, const Real* y);
  int check_derivative(Real t, Real* ydot);

  Real inject_from_ = std::numeric_limits<Real>::infinity();
  bool own_error_ = false;
  std::string error_;
  long failures_ = 0;
  long particle_evals_ = 0;
};

}  // namespace sphark
