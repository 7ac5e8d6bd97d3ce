// Root location on the leapfrog trajectory (leapfrog_stepper.hpp): Illinois iteration on the
// length of the last step.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "leapfrog_stepper.hpp"

namespace sphark::detail {

bool LeapfrogStepper::locate_root(Real dt) {
  if (!eval_roots(t_ + dt)) return false;
  if (!any_crossed()) return false;
  const std::vector<Real> g_end = g_new_;
  Real tau = dt;
  for (std::size_t k = 0; k < g_.size() && !failed_; ++k)
    if (crossed(g_[k], g_end[k])) tau = std::min(tau, illinois(k, dt, g_end[k]));
  if (failed_ || interrupted_) return false;
  if (step(tau) != 0) return fail("RHS during root location"), false;
  if (!eval_roots(t_ + tau)) return false;
  roots_.assign(g_.size(), 0);
  for (std::size_t k = 0; k < g_.size(); ++k)
    if (crossed(g_[k], g_new_[k])) roots_[k] = g_new_[k] > g_[k] ? 1 : -1;
  accept(tau);
  return true;
}

bool LeapfrogStepper::eval_roots(Real t) {
  if (call("roots", t, [&] { return system_.roots(t, y_new_.data(), g_new_.data()); }) == 0) return true;
  fail("root functions");
  return false;
}

bool LeapfrogStepper::any_crossed() const {
  for (std::size_t k = 0; k < g_.size(); ++k)
    if (crossed(g_[k], g_new_[k])) return true;
  return false;
}

Real LeapfrogStepper::illinois(std::size_t k, Real dt, Real g_dt) {
  Real lo = 0, hi = dt, g_lo = g_[k], g_hi = g_dt;
  const Real tol = 100 * std::numeric_limits<Real>::epsilon() * (std::abs(t_) + dt);
  int side = 0;
  for (int it = 0; it < kMaxRootIterations && hi - lo > tol && g_hi != 0; ++it) {
    if (interrupt_now()) return hi;
    const Real tau = std::clamp(hi - g_hi * (hi - lo) / (g_hi - g_lo), lo + 0.25 * tol, hi - 0.25 * tol);
    if (step(tau) != 0) return fail("RHS during root location"), dt;
    if (!eval_roots(t_ + tau)) return dt;
    const Real g = g_new_[k];
    if (crossed(g_[k], g)) {
      hi = tau, g_hi = g;
      if (side == 1) g_lo *= 0.5;  // Illinois: halve the stale end
      side = 1;
    } else {
      lo = tau, g_lo = g;
      if (side == -1) g_hi *= 0.5;
      side = -1;
    }
  }
  return hi;
}

}  // namespace sphark::detail
