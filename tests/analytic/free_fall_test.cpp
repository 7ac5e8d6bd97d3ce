// Exact pressureless free fall: r(0) = r0 and r(t_c) = 0 exactly, t_c = t_ff of the mean
// density, a known point of the parametric solution (xi = pi/4: r = r0/2 at
// t = (pi/4 + 1/2) tau), dr/dt by finite differences against the energy equation
// v^2 = 2 G M (1/r - 1/r0), the inversion t <-> r to round-off (within its conditioning), and
// the homologous Lagrangian radii of a uniform sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "sphark/analytic/free_fall.hpp"

using namespace sphark;

namespace {
constexpr Real kEps = std::numeric_limits<Real>::epsilon();
}

TEST(FreeFall, EndPointsAndFreeFallTime) {
  const Real r0 = 2.5, M = 3.0, G = 0.7;
  const FreeFallShell shell(r0, M, G);
  EXPECT_EQ(shell.radius(0), r0);
  EXPECT_EQ(shell.radius(shell.collapse_time()), 0.0);
  EXPECT_EQ(shell.radius(1.5 * shell.collapse_time()), 0.0);
  const Real rho = 3 * M / (4 * kPi * r0 * r0 * r0);
  EXPECT_NEAR(shell.collapse_time() / free_fall_time(rho, G), 1.0, 4 * kEps);
  EXPECT_THROW(shell.radius(-1e-3), std::invalid_argument);
  EXPECT_THROW(FreeFallShell(0.0, 1.0), std::invalid_argument);
}

TEST(FreeFall, HalfRadiusAtXiQuarterPi) {
  const FreeFallShell shell(1.0, 1.0);
  const Real t = (0.25 * kPi + 0.5) * shell.time_scale();  // xi = pi/4: cos^2 = 1/2
  EXPECT_NEAR(shell.radius(t), 0.5, 8 * kEps);
  EXPECT_NEAR(shell.time_at_radius(0.5), t, 8 * kEps * t);
}

TEST(FreeFall, DerivativeSatisfiesTheEnergyEquation) {
  const Real r0 = 1.3, M = 0.8;
  const FreeFallShell shell(r0, M);
  const Real tc = shell.collapse_time();
  for (Real f : {0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 0.999}) {
    const Real t = f * tc, r = shell.radius(t);
    const Real v_energy = -std::sqrt(2 * M * (1 / r - 1 / r0));
    // 1/r - 1/r0 cancels where r ~ r0: its relative round-off is ~ eps r0 / (r0 - r)
    EXPECT_NEAR(shell.velocity(t) / v_energy, 1.0, 16 * kEps * (1 + r0 / (r0 - r))) << f;
    const Real d = 1e-4 * (tc - t);  // central difference, step well inside (0, t_c)
    const Real fd = (shell.radius(t + d) - shell.radius(t - d)) / (2 * d);
    EXPECT_NEAR(fd / v_energy, 1.0, 1e-7) << f;
  }
}

TEST(FreeFall, InversionIsExactToRoundOff) {
  const Real r0 = 1.0, M = 1.0;
  const FreeFallShell shell(r0, M);
  const Real tc = shell.collapse_time();
  // r(t(r)) = r: the error of t(r) (a few ulps of t) propagates through |dr/dt|
  for (Real r = 1e-9; r < r0; r *= 1.7) {
    const Real t = shell.time_at_radius(r);
    const Real back = shell.radius(t);
    const Real v = std::abs(shell.velocity(t));
    EXPECT_LE(std::abs(back - r), 8 * kEps * (r + v * t)) << r;
  }
  // t(r(t)) = t: the error of r(t) propagates through |dt/dr| = 1 / |v|
  for (Real f : {1e-6, 1e-3, 0.05, 0.2, 0.5, 0.8, 0.95, 0.999, 1 - 1e-6, 1 - 1e-10}) {
    const Real t = f * tc, r = shell.radius(t);
    const Real v = std::abs(shell.velocity(t));
    EXPECT_LE(std::abs(shell.time_at_radius(r) - t), 8 * kEps * (t + r / v)) << f;
  }
  // the inner equation G(eta) = g itself, over 16 decades of g: eta within 2 ulps of the root
  for (Real g = 1e-16; g < 0.5 * kPi; g *= 3.1) {
    const Real eta = free_fall_g_inverse(g), ulp = std::nextafter(eta, 1.0) - eta;
    EXPECT_LT(free_fall_g(eta - 2 * ulp), g) << g;
    EXPECT_GT(free_fall_g(eta + 2 * ulp), g) << g;
  }
  EXPECT_EQ(free_fall_g_inverse(0.5 * kPi), 0.5 * kPi);
}

TEST(FreeFall, SeriesMatchesTheClosedFormWhereBothAreAccurate) {
  for (Real eta : {0.3, 0.4, 0.49}) {
    const Real closed = eta - std::sin(eta) * std::cos(eta);
    EXPECT_NEAR(free_fall_g(eta), closed, 32 * kEps * eta) << eta;  // closed form loses ~eta / G digits
  }
  const Real e = 1e-4, series = 2 * std::pow(e, 3) / 3 - 2 * std::pow(e, 5) / 15 + 4 * std::pow(e, 7) / 315;
  EXPECT_NEAR(free_fall_g(e), series, 4 * kEps * series);
}

TEST(FreeFall, UniformSphereCollapsesHomologously) {
  const Real R = 2.0, M = 5.0;
  const Real tff = free_fall_time(3 * M / (4 * kPi * R * R * R));
  for (Real f : {0.1, 0.5, 0.9, 1.0}) {
    EXPECT_NEAR(uniform_sphere_lagrangian_radius(f, R, M, 0), std::cbrt(f) * R, 4 * kEps * R);
    // t_ff and the shell's t_c agree to a few ulps; r ~ r0 (3 (t_c - t) / (2 tau))^(2/3) there
    EXPECT_LE(uniform_sphere_lagrangian_radius(f, R, M, tff), R * std::pow(16 * kEps, 2.0 / 3.0));
    EXPECT_EQ(uniform_sphere_lagrangian_radius(f, R, M, 1.01 * tff), 0.0);
    for (Real s : {0.3, 0.6, 0.9}) {
      const Real ratio = uniform_sphere_lagrangian_radius(f, R, M, s * tff) /
                         uniform_sphere_lagrangian_radius(1.0, R, M, s * tff);
      EXPECT_NEAR(ratio, std::cbrt(f), 16 * kEps) << f << " " << s;
    }
  }
  EXPECT_THROW(uniform_sphere_lagrangian_radius(0.0, R, M, 0), std::invalid_argument);
}
