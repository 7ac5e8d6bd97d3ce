#pragma once
// Ghost maps across a curved wall, acting on the wall-normal coordinate s only (seed 004, eq. 9).
//
//   mirror          psi0(s) = -s                                   seed 004, eq. (15)/(16)
//   density map     psi' = -J(s)/J(psi), psi(0) = 0                seed 004, eqs. (12)-(13)
//
// Every closed form below has the canonical form g(rho(psi)) + g(rho(s)) = 2 g(rho0)
// (seed 004, eq. 30) with rho the radial coordinate of the wall (rho = R + s for fluid inside,
// rho = R - s for fluid outside an obstacle) and g' proportional to the Jacobian. A map can leave
// its valid range (the ghost would have to cross the symmetry axis / centre line, or no real
// solution exists); it then returns the limiting value together with a status != Ok, never NaN.
#include <cmath>
#include <limits>
#include <string_view>

#include "sphark/core/types.hpp"

namespace sphark {

// Which side of the wall the fluid is on: inside a pipe / ball / torus tube, or outside an
// obstacle. s < 0 is always the fluid side.
enum class FluidSide { Inside, Outside };

// +1: rho = rho0 + s (fluid inside), -1: rho = rho0 - s (fluid outside).
inline constexpr Real side_sign(FluidSide side) { return side == FluidSide::Inside ? 1.0 : -1.0; }

enum class MapStatus {
  Ok,
  BeyondAxis,      // the ghost would be placed across the axis of symmetry (torus, R/a < 2)
  NoRealSolution,  // g(rho') = c has no root rho' >= 0: the ghost side has too little volume
};

std::string_view to_string(MapStatus status);

struct MapResult {
  Real psi = 0;  // ghost coordinate s' (> 0 for s < 0); the limiting value when status != Ok
  MapStatus status = MapStatus::Ok;
  bool ok() const { return status == MapStatus::Ok; }
};

inline constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

// seed 004, eq. (15)
inline MapResult mirror_map(Real s) { return {-s, MapStatus::Ok}; }

// Cylinder (or 2D circle) of radius R, J = rho: seed 004, eq. (21)
//   psi = sqrt(2R^2 - (R+s)^2) - R, written without cancellation as
//   psi = -s (2R + s) / (sqrt(2R^2 - (R+s)^2) + R)   (fluid inside; s -> -s, psi -> -psi outside).
inline MapResult cylinder_map(Real s, Real R, FluidSide side) {
  const Real sg = side_sign(side);
  const Real t = sg * s;  // rho - R
  const Real q2 = 2 * R * R - (R + t) * (R + t);
  if (q2 < 0) return {sg * (-R), MapStatus::NoRealSolution};  // ghost would pass the axis
  const Real dt = -t * (2 * R + t) / (std::sqrt(q2) + R);     // rho' - R
  return {sg * dt, MapStatus::Ok};
}

// cbrt(y) by a quadratic guess on [1, 2] and two Halley steps q <- q (q^3 + 2y) / (2q^3 + y)
// (guess error < 1e-3, then < 1e-9, then round-off), for y in [1, 2]: the range of
// (2R^3 - rho^3)/R^3 for fluid inside a sphere. Elsewhere std::cbrt.
inline Real cbrt_1_2(Real y) {
  Real q = 0.62208 + y * (0.43692 - 0.05900 * y);
  for (int it = 0; it < 2; ++it) {
    const Real q3 = q * q * q;
    q *= (q3 + 2 * y) / (2 * q3 + y);
  }
  return q;
}
inline Real cube_root(Real q3, Real R) {
  const Real R3 = R * R * R;
  if (q3 >= R3 && q3 <= 2 * R3) return R * cbrt_1_2(q3 / R3);
  return std::cbrt(q3);
}

// Sphere of radius R, J = rho^2 sin(phi): seed 004, eq. (25)
//   psi = cbrt(2R^3 - (R+s)^3) - R = -s (rho^2 + rho R + R^2) / (q^2 + q R + R^2), q = cbrt(.)
inline MapResult sphere_map(Real s, Real R, FluidSide side) {
  const Real sg = side_sign(side);
  const Real t = sg * s;
  const Real rho = R + t;
  const Real q3 = 2 * R * R * R - rho * rho * rho;
  if (q3 < 0) return {sg * (-R), MapStatus::NoRealSolution};  // ghost would pass the centre
  const Real q = cube_root(q3, R);
  const Real dt = -t * (rho * rho + rho * R + R * R) / (q * q + q * R + R * R);
  return {sg * dt, MapStatus::Ok};
}

// Largest real root z >= 1/sqrt(3) of the depressed cubic z^3 - z = k, the branch through
// z(0) = 1, for k >= -2/(3 sqrt 3) (Viete's trigonometric / hyperbolic forms; no cancellation at
// k -> 0 and continuous through the change of form at k = 2/(3 sqrt 3)).
Real depressed_cubic_root(Real k);
// The same root by Halley steps from its Taylor series (two for |k| <= 1/4, three up to
// kTorusFastK); agrees with depressed_cubic_root to round-off there (tests/boundaries/maps_test.cpp).
inline constexpr Real kTorusFastK = 0.35;
inline constexpr Real kCubicFoldK = -0.38490017945975050;  // -2 / (3 sqrt 3)
inline Real depressed_cubic_root_fast(Real k) {
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

// Inverse of the toroidal g(x) = Bu x^3/3 + x^2/2 (seed 004, eq. 29) on its increasing branch
// 0 <= x <= 1/|Bu| (Bu < 0) or x >= 0 (Bu >= 0), i.e. the ghost stays on the fluid's side of the
// torus axis. Equivalent to seed 004, eqs. (41)-(47), rewritten as x = sqrt(2c) / z with
// z^3 - z = k, k = (2/3) Bu sqrt(2c), which is exact at Bu = 0 (x = sqrt(2c), eq. 44) instead of
// the 0/0 of eq. (45). Returns NoRealSolution for c < 0 and BeyondAxis for k below the fold.
inline MapResult torus_g_inverse(Real c, Real Bu) {
  if (c < 0) return {0, MapStatus::NoRealSolution};
  const Real r = std::sqrt(2 * c);  // the cylinder's inverse, seed 004 eq. (44)
  const Real k = (2.0 / 3.0) * Bu * r;
  if (k < kCubicFoldK) return {1 / std::abs(Bu), MapStatus::BeyondAxis};
  const Real z = std::abs(k) <= kTorusFastK ? depressed_cubic_root_fast(k) : depressed_cubic_root(k);
  return {r / z, MapStatus::Ok};
}

// Torus of minor radius a, major radius R, at poloidal angle u (cos_u = cos u, u = 0 on the
// outer equator): J = rho (R + rho cos u), Bu = cos(u)/R, seed 004, eqs. (27)-(29), (38)-(47).
inline MapResult torus_map(Real s, Real a, Real R, Real cos_u, FluidSide side) {
  // seed 004, eqs. (28)-(29): g(rho') = 2 g(a) - g(rho), g(x) = Bu x^3/3 + x^2/2, Bu = cos(u)/R.
  const Real sg = side_sign(side);
  const Real Bu = cos_u * (1 / R);  // 1/R is hoisted out of a ghost loop
  const Real t = sg * s;            // rho - a
  // g(a + d) - g(a) = d q(d), q(d) = Bu (3a^2 + 3a d + d^2)/3 + a + d/2: differences without
  // cancellation, so that psi(0) = 0 exactly and psi keeps its relative accuracy near the wall.
  const auto q = [&](Real d) { return Bu * (a * a + a * d + d * d / 3) + a + d / 2; };
  const Real dg = t * q(t);  // g(rho) - g(a)
  const Real ga = a * a * (Bu * a / 3 + 0.5);
  const MapResult inv = torus_g_inverse(ga - dg, Bu);  // rho' = g^-1(2 g(a) - g(rho))
  if (!inv.ok()) return {sg * (inv.psi - a), inv.status};
  // One refinement of d' = rho' - a from g(a + d') - g(a) = -dg (a secant step through 0).
  const Real d0 = inv.psi - a;
  const Real q0 = q(d0);
  const Real d1 = q0 > 0 ? -dg / q0 : d0;
  return {sg * d1, MapStatus::Ok};
}

}  // namespace sphark
