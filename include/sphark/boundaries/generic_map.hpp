#pragma once
// The density-preserving map for any wall that supplies its Jacobian J(s) along a normal line
// (u, v fixed): seed 004, eq. (13) integrated once,
//   G(psi) = -G(s),   G(t) = integral_0^t J(tau) dtau        (seed 004, eqs. 19, 24, 28 in general)
// G is evaluated by adaptive Gauss-Legendre quadrature and inverted by Newton's method
// (G' = J > 0) safeguarded by bisection on the bracket [0, psi_max].
#include <functional>

#include "sphark/boundaries/maps.hpp"

namespace sphark {

using JacobianFn = std::function<Real(Real s)>;

// integral_a^b J(t) dt by adaptive 10-point Gauss-Legendre (relative tolerance ~1e-14;
// exact to round-off for polynomial J of degree <= 19).
Real integrate_jacobian(const JacobianFn& J, Real a, Real b);

struct GenericMapOptions {
  int max_iterations = 200;
  Real tolerance = 1e-15;  // on |delta psi| relative to max(1, |psi|)
};

// psi(s) for s <= 0 with psi in [0, psi_max] (psi_max = kInfinity if the ghost side is unbounded).
// J must be positive on (s, 0] and on [0, psi_max). Returns NoRealSolution (psi = psi_max) if
// G(psi_max) < -G(s): the ghost side has less volume than the fluid side needs.
MapResult generic_map(const JacobianFn& J, Real s, Real psi_max, const GenericMapOptions& opt = {});

}  // namespace sphark
