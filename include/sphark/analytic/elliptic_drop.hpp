#pragma once
// Exact (incompressible) solution of the 2D elliptic drop in a harmonic trap.
//
// An incompressible drop with velocity v = (-A(t) x, A(t) y), semi-axes a(t) along x and b(t)
// along y (a b = R^2), pressure p = p0(t) (1 - x^2/a^2 - y^2/b^2) and body force -omega^2 r.
// The Euler equations reduce to (derivation in docs/water_drop.md):
//   da/dt = -A a,   db/dt = A b,
//   dA/dt = (A^2 + omega^2) (a^2 - b^2) / (a^2 + b^2),
//   p0    = rho a^2 (A^2 - dA/dt + omega^2) / 2    (must stay >= 0: the drop holds together).
// Monaghan & Rafiee (2013) and Colagrossi (2005) use the trap-free variant (omega = 0).
#include <vector>

#include "sphark/core/types.hpp"

namespace sphark {

struct EllipticDropState {
  Real t, a, b, A;
};

class EllipticDrop {
 public:
  EllipticDrop(Real radius, Real amplitude, Real omega) : R_(radius), A0_(amplitude), omega_(omega) {}

  // State at time t, integrated with classical RK4 from t = 0 on the grid t_k = k max_step, the
  // last step ending at t (the error of the default is below 1e-12 relative for the seed's
  // parameters). A function of (t, max_step) alone; the last grid state is kept, so a run that
  // asks at increasing times costs one integration in all, not one from t = 0 per call (not
  // thread-safe: one object per thread).
  EllipticDropState at(Real t, Real max_step = 1e-6) const;

  // Central pressure p0(t) / rho.
  Real central_pressure_over_rho(const EllipticDropState& s) const;

  // Right-hand side of the (a, b, A) system.
  void derivative(const Real y[3], Real dy[3]) const;

 private:
  void rk4_step(Real y[3], Real dt) const;

  struct GridState {
    Real step = 0;  // the grid spacing of k and y (0: none yet)
    long k = 0;     // y is the state at t_k = k step
    Real y[3] = {0, 0, 0};
  };
  Real R_, A0_, omega_;
  mutable GridState grid_;
};

}  // namespace sphark
