#include "sphark/analytic/free_fall.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace sphark {

Real free_fall_time(Real density, Real G) {
  if (!(density > 0) || !(G > 0)) throw std::invalid_argument("free_fall_time: density and G must be positive");
  return std::sqrt(3 * kPi / (32 * G * density));
}

FreeFallShell::FreeFallShell(Real r0, Real enclosed_mass, Real G) : r0_(r0), mass_(enclosed_mass), G_(G) {
  if (!(r0 > 0) || !(enclosed_mass > 0) || !(G > 0))
    throw std::invalid_argument("FreeFallShell: r0, the enclosed mass and G must be positive");
  tau_ = std::sqrt(r0 * r0 * r0 / (2 * G * enclosed_mass));
}

Real free_fall_g(Real eta) {
  if (eta >= 0.5) return eta - std::sin(eta) * std::cos(eta);
  // sum_{n>=1} (-1)^(n+1) 2^(2n) eta^(2n+1) / (2n+1)!
  const Real x2 = 4 * eta * eta;
  Real term = 2 * eta * eta * eta / 3, sum = 0;
  for (int n = 1; n < 40 && std::abs(term) > 1e-18 * std::abs(sum); ++n) {
    sum += term;
    term *= -x2 / ((2 * n + 2) * (2 * n + 3));
  }
  return sum;
}

Real free_fall_g_inverse(Real g) {
  const Real half_pi = 0.5 * kPi;
  if (!(g >= 0) || g > half_pi) throw std::invalid_argument("free_fall_g_inverse: need 0 <= g <= pi/2");
  if (g == 0) return 0;
  if (g == half_pi) return half_pi;
  Real lo = 0, hi = half_pi;
  // G <= 2 eta^3 / 3 on [0, pi/2] (alternating series, decreasing terms): the cube-root guess
  // lies left of the root; Newton on the convex G then approaches from the right.
  Real eta = std::min(half_pi, std::cbrt(1.5 * g));
  Real best = eta, best_residual = std::numeric_limits<Real>::infinity();
  for (int it = 0; it < 100; ++it) {
    const Real residual = free_fall_g(eta) - g;
    if (std::abs(residual) < best_residual) best = eta, best_residual = std::abs(residual);
    if (residual == 0) break;
    (residual > 0 ? hi : lo) = eta;
    const Real s = std::sin(eta);
    Real next = eta - residual / (2 * s * s);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);  // bisection when Newton leaves the bracket
    if (next == eta || !(lo < next && next < hi)) break;  // converged to round-off: the bracket is two ulps
    eta = next;
  }
  return best;  // the iterate with the smallest |G(eta) - g| (Newton ends oscillating by an ulp)
}

Real FreeFallShell::eta(Real t) const {
  if (!(t >= 0)) throw std::invalid_argument("FreeFallShell: time must be >= 0");
  const Real remaining = collapse_time() - t;
  if (remaining <= 0) return 0;
  return free_fall_g_inverse(std::min(0.5 * kPi, remaining / tau_));
}

Real FreeFallShell::radius(Real t) const {
  if (t == 0) return r0_;
  const Real s = std::sin(eta(t));
  return r0_ * s * s;
}

Real FreeFallShell::velocity(Real t) const {
  const Real e = eta(t);
  if (e == 0) return -std::numeric_limits<Real>::infinity();
  return -(r0_ / tau_) * std::cos(e) / std::sin(e);  // tan(xi) = cot(eta)
}

Real FreeFallShell::time_at_radius(Real r) const {
  if (!(r >= 0) || r > r0_) throw std::invalid_argument("FreeFallShell::time_at_radius: need 0 <= r <= r0");
  const Real e = std::atan2(std::sqrt(r), std::sqrt(r0_ - r));  // sin^2(eta) = r / r0, accurate at both ends
  return tau_ * (0.5 * kPi - free_fall_g(e));
}

Real uniform_sphere_lagrangian_radius(Real mass_fraction, Real R, Real M, Real t, Real G) {
  if (!(mass_fraction > 0) || mass_fraction > 1)
    throw std::invalid_argument("uniform_sphere_lagrangian_radius: mass fraction must lie in (0, 1]");
  return FreeFallShell(std::cbrt(mass_fraction) * R, mass_fraction * M, G).radius(t);
}

}  // namespace sphark
