#pragma once
// Exact pressureless free fall (the cold collapse of a uniform sphere; issue #15).
//
// A mass shell released at rest at radius r0 around an enclosed mass M (constant as long as
// shells do not cross, which holds for a uniform sphere: all shells fall homologously) obeys
// v^2 = 2 G M (1/r - 1/r0), whose parametric solution is
//   r = r0 cos^2(xi),   t = (xi + sin xi cos xi) tau,   tau = sqrt(r0^3 / (2 G M)),
// for xi in [0, pi/2]; the shell reaches the centre at t_c = (pi/2) tau, which for the mean
// density rho = 3 M / (4 pi r0^3) is t_ff = sqrt(3 pi / (32 G rho)).
//
// Inversion. With eta = pi/2 - xi the solution reads r = r0 sin^2(eta) and
//   G(eta) := eta - sin(eta) cos(eta) = (t_c - t) / tau,
// increasing and convex on [0, pi/2] (G' = 2 sin^2 eta, G'' = 4 sin eta cos eta). G is
// evaluated by its series 2 eta^3/3 - 2 eta^5/15 + ... for eta < 1/2 (no cancellation near the
// collapse, where r ~ r0 (3 (t_c - t) / (2 tau))^(2/3)), and solved by Newton's method kept
// inside a bisection bracket.
#include "sphark/core/types.hpp"

namespace sphark {

// t_ff = sqrt(3 pi / (32 G rho)).
Real free_fall_time(Real density, Real G = 1);

class FreeFallShell {
 public:
  // Throws std::invalid_argument unless r0 > 0, enclosed_mass > 0, G > 0.
  FreeFallShell(Real r0, Real enclosed_mass, Real G = 1);

  Real time_scale() const { return tau_; }             // tau = sqrt(r0^3 / (2 G M))
  Real collapse_time() const { return 0.5 * kPi * tau_; }  // t_c = (pi/2) tau
  Real initial_radius() const { return r0_; }

  // r(t); r(0) = r0, r = 0 for t >= t_c. Throws std::invalid_argument for t < 0.
  Real radius(Real t) const;
  // dr/dt = -(r0 / tau) tan(xi) (= -sqrt(2 G M (1/r - 1/r0))); -infinity at t >= t_c.
  Real velocity(Real t) const;
  // The inverse: t at which the shell is at r, for 0 <= r <= r0 (throws otherwise).
  Real time_at_radius(Real r) const;
  // eta = pi/2 - xi at time t (in [0, pi/2]).
  Real eta(Real t) const;

 private:
  Real r0_, mass_, G_, tau_;
};

// G(eta) = eta - sin(eta) cos(eta), accurate to round-off for small eta (series).
Real free_fall_g(Real eta);
// Its inverse on [0, pi/2]: eta with G(eta) = g, for 0 <= g <= pi/2.
Real free_fall_g_inverse(Real g);

// Lagrangian radius enclosing the mass fraction f (0 < f <= 1) of a uniform sphere of radius R
// and mass M, released from rest, at time t: f^(1/3) R sin^2(eta(t)), the same eta for every
// shell (t_c = t_ff of the sphere for all of them).
Real uniform_sphere_lagrangian_radius(Real mass_fraction, Real R, Real M, Real t, Real G = 1);

}  // namespace sphark
