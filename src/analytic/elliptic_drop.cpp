#include "sphark/analytic/elliptic_drop.hpp"

#include <cmath>

namespace sphark {

void EllipticDrop::derivative(const Real y[3], Real dy[3]) const {
  const Real a = y[0], b = y[1], A = y[2];
  dy[0] = -A * a;
  dy[1] = A * b;
  dy[2] = (A * A + omega_ * omega_) * (a * a - b * b) / (a * a + b * b);
}

void EllipticDrop::rk4_step(Real y[3], Real dt) const {
  Real k1[3], k2[3], k3[3], k4[3], tmp[3];
  derivative(y, k1);
  for (int i = 0; i < 3; ++i) tmp[i] = y[i] + 0.5 * dt * k1[i];
  derivative(tmp, k2);
  for (int i = 0; i < 3; ++i) tmp[i] = y[i] + 0.5 * dt * k2[i];
  derivative(tmp, k3);
  for (int i = 0; i < 3; ++i) tmp[i] = y[i] + dt * k3[i];
  derivative(tmp, k4);
  for (int i = 0; i < 3; ++i) y[i] += dt / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
}

// RK4 on the grid t_k = k max_step up to the last grid time <= t, then one step to t. The last
// grid state reached is kept, so later (larger) times continue from it instead of from t = 0;
// the result is the same whatever was asked before (a function of t and max_step alone).
EllipticDropState EllipticDrop::at(Real t, Real max_step) const {
  const long k_end = t > 0 ? static_cast<long>(std::floor(t / max_step)) : 0;
  GridState& g = grid_;
  if (g.step != max_step || g.k > k_end) g = {max_step, 0, {R_, R_, A0_}};
  for (; g.k < k_end; ++g.k) rk4_step(g.y, max_step);
  Real y[3] = {g.y[0], g.y[1], g.y[2]};
  const Real rest = t - static_cast<Real>(k_end) * max_step;
  if (rest > 0) rk4_step(y, rest);
  return {t, y[0], y[1], y[2]};
}

Real EllipticDrop::central_pressure_over_rho(const EllipticDropState& s) const {
  Real y[3] = {s.a, s.b, s.A}, dy[3];
  derivative(y, dy);
  return 0.5 * s.a * s.a * (s.A * s.A - dy[2] + omega_ * omega_);
}

}  // namespace sphark
