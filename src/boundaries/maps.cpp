#include "sphark/boundaries/maps.hpp"

#include <algorithm>

namespace sphark {

std::string_view to_string(MapStatus status) {
  switch (status) {
    case MapStatus::Ok: return "ok";
    case MapStatus::BeyondAxis: return "ghost would cross the axis of symmetry";
    case MapStatus::NoRealSolution: return "no real solution (not enough volume on the ghost side)";
  }
  return "?";
}

Real depressed_cubic_root(Real k) {
  // z = (2/sqrt3) cos(acos(v)/3) for |v| <= 1, (2/sqrt3) cosh(acosh(v)/3) for v > 1,
  // v = (3 sqrt3 / 2) k (Viete). Largest real root of z^3 - z - k = 0.
  const Real sqrt3 = std::sqrt(3.0);
  const Real v = 1.5 * sqrt3 * k;
  if (v > 1) return 2 / sqrt3 * std::cosh(std::acosh(v) / 3);
  return 2 / sqrt3 * std::cos(std::acos(std::max(v, Real(-1))) / 3);
}

Real depressed_cubic_root_fast(Real k) {
  // Taylor series z = 1 + k/2 - 3k^2/8 + k^3/2 + O(k^4), then Halley's iteration on
  // f(z) = z^3 - z - k (cubic convergence: |k| <= 1/4 gives an initial error < 3e-3, then
  // < 1e-7, then round-off; |k| <= 0.35: a third step, measured error < 5e-16).
  Real z = 1 + k * (0.5 + k * (-0.375 + 0.5 * k));
  const int steps = std::abs(k) <= 0.25 ? 2 : 3;
  for (int it = 0; it < steps; ++it) {
    const Real f = z * z * z - z - k;
    const Real df = 3 * z * z - 1;
    z -= 2 * f * df / (2 * df * df - 6 * z * f);
  }
  return z;
}

MapResult torus_g_inverse(Real c, Real Bu) {
  if (c < 0) return {0, MapStatus::NoRealSolution};
  const Real r = std::sqrt(2 * c);  // the cylinder's inverse, seed 004 eq. (44)
  const Real k = (2.0 / 3.0) * Bu * r;
  if (k < kCubicFoldK) return {1 / std::abs(Bu), MapStatus::BeyondAxis};
  const Real z = std::abs(k) <= kTorusFastK ? depressed_cubic_root_fast(k) : depressed_cubic_root(k);
  return {r / z, MapStatus::Ok};
}

MapResult torus_map(Real s, Real a, Real R, Real cos_u, FluidSide side) {
  // seed 004, eqs. (28)-(29): g(rho') = 2 g(a) - g(rho), g(x) = Bu x^3/3 + x^2/2, Bu = cos(u)/R.
  const Real sg = side_sign(side);
  const Real Bu = cos_u / R;
  const Real t = sg * s;  // rho - a
  // g(a + d) - g(a) = d q(d), q(d) = Bu (3a^2 + 3a d + d^2)/3 + a + d/2: differences without
  // cancellation, so that psi(0) = 0 exactly and psi keeps its relative accuracy near the wall.
  const auto q = [&](Real d) { return Bu * (3 * a * a + 3 * a * d + d * d) / 3 + a + d / 2; };
  const Real dg = t * q(t);  // g(rho) - g(a)
  const Real ga = a * a * (Bu * a / 3 + 0.5);
  const MapResult inv = torus_g_inverse(ga - dg, Bu);  // rho' = g^-1(2 g(a) - g(rho))
  if (!inv.ok()) return {sg * (inv.psi - a), inv.status};
  // One refinement of d' = rho' - a from g(a + d') - g(a) = -dg (a secant step, error ~ eps |d'|).
  const Real d0 = inv.psi - a;
  const Real q0 = q(d0);
  const Real d1 = q0 > 0 ? -dg / q0 : d0;
  return {sg * d1, MapStatus::Ok};
}

}  // namespace sphark
