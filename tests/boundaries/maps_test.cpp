// Exact properties of the ghost maps (seed 004, §3-5, Appendix A-B).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "sphark/boundaries/generic_map.hpp"
#include "sphark/boundaries/walls.hpp"

using namespace sphark;

namespace {

struct Case {
  std::string name;
  Wall<3> wall;
  Real u;      // poloidal angle for the torus, unused otherwise
  Real s_min;  // fluid points tested: s in [s_min, 0]
};

// Every closed-form map, both fluid sides, the torus at several poloidal angles and aspect ratios.
std::vector<Case> cases() {
  std::vector<Case> c;
  c.push_back({"plane", Plane<3>{}, 0, -1});
  c.push_back({"cylinder_in", Cylinder<3>{Vec<3>::Zero(), 1, FluidSide::Inside}, 0, -1});
  c.push_back({"cylinder_out", Cylinder<3>{Vec<3>::Zero(), 1, FluidSide::Outside}, 0, -0.4});
  c.push_back({"sphere_in", Sphere{Vec<3>::Zero(), 1, FluidSide::Inside}, 0, -1});
  c.push_back({"sphere_out", Sphere{Vec<3>::Zero(), 1, FluidSide::Outside}, 0, -0.25});
  for (Real ratio : {2.5, 3.0, 10.0})
    for (Real u : {0.0, 0.7, kPi / 2, 2.0, kPi}) {
      const std::string tag = "_R" + std::to_string(ratio).substr(0, 4) + "_u" + std::to_string(u).substr(0, 4);
      c.push_back({"torus_in" + tag, Torus{Vec<3>::Zero(), ratio, 1, FluidSide::Inside}, u, -1});
      c.push_back({"torus_out" + tag, Torus{Vec<3>::Zero(), ratio, 1, FluidSide::Outside}, u, -0.25});
    }
  return c;
}

MapResult closed(const Case& c, Real s) {
  return std::visit([&](const auto& w) { return w.map(s, c.u, 0.0); }, c.wall);
}
Real jac(const Case& c, Real s) {
  return std::visit([&](const auto& w) { return w.jacobian(s, c.u, 0.0); }, c.wall);
}

}  // namespace

// seed 004, eq. (12) and §5: psi(0) = 0 and psi'(0) = -1 (mirror-like at the wall).
TEST(GhostMaps, ZeroAtWallAndMirrorSlope) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    EXPECT_EQ(closed(c, 0.0).psi, 0.0);
    EXPECT_EQ(generic_wall_map(c.wall, 0.0, c.u, 0).psi, 0.0);
    // One-sided second-order difference (3 psi(0) - 4 psi(-d) + psi(-2d)) / (2d): truncation
    // d^2 |psi'''(0)| / 3 with psi'''(0) = -6/R^2 (cylinder), -24/R^2 (sphere; from the series
    // psi = -s - 2s^2/R - 4s^3/R^2), the torus in between; round-off ~8 eps |psi(-d)| / (2d).
    const Real d = 1e-6;
    const Real fd = (3 * closed(c, 0).psi - 4 * closed(c, -d).psi + closed(c, -2 * d).psi) / (2 * d);
    EXPECT_NEAR(fd, -1.0, 24 * d * d / 3 + 4 * 8 * 2.2e-16);
  }
  EXPECT_EQ(mirror_map(-0.3).psi, 0.3);
}

// Each closed form satisfies the ODE (13): psi' = -J(s)/J(psi), by central differences.
TEST(GhostMaps, ClosedFormsSatisfyEquation13) {
  const Real d = 1e-6;  // truncation d^2 |psi'''| / 6 < 1e-9 up to the obstacle limits; round-off ~1e-10
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    for (int k = 1; k < 20; ++k) {
      const Real s = c.s_min * (0.05 + 0.9 * k / 20.0);
      const MapResult m = closed(c, s);
      ASSERT_TRUE(m.ok()) << "s = " << s;
      const Real fd = (closed(c, s + d).psi - closed(c, s - d).psi) / (2 * d);
      const Real ode = -jac(c, s) / jac(c, m.psi);
      EXPECT_NEAR(fd, ode, 1e-8 * std::abs(ode)) << "s = " << s;
    }
  }
}

// The generic quadrature + safeguarded Newton map reproduces every closed form to 1e-12.
TEST(GhostMaps, GenericNewtonEqualsClosedForms) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    for (int k = 0; k <= 40; ++k) {
      const Real s = c.s_min * k / 40.0;
      const MapResult a = closed(c, s), b = generic_wall_map(c.wall, s, c.u, 0);
      ASSERT_TRUE(a.ok() && b.ok()) << "s = " << s;
      EXPECT_NEAR(a.psi, b.psi, 1e-12) << "s = " << s;
    }
  }
}

// The measure identity J(s) ds = -J(psi) dpsi, integrated between two fluid points s1 < s2:
// int_{s1}^{s2} J = int_{psi(s2)}^{psi(s1)} J (the volumes of fluid slab and ghost slab agree).
TEST(GhostMaps, MeasureIdentity) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const JacobianFn J = [&](Real s) { return jac(c, s); };
    for (int k = 0; k < 10; ++k) {
      const Real s1 = c.s_min * (1 - 0.1 * k), s2 = s1 * 0.5;
      const Real p1 = closed(c, s1).psi, p2 = closed(c, s2).psi;
      const Real fluid = integrate_jacobian(J, s1, s2), ghost = integrate_jacobian(J, p2, p1);
      EXPECT_NEAR(fluid, ghost, 1e-13 * std::abs(fluid) + 1e-15) << "s1 = " << s1;
    }
  }
}

// seed 004, Appendix B (eq. 52): at u = +-pi/2 the torus map is the cylinder map, for any R/a.
TEST(GhostMaps, TorusEqualsCylinderAtHalfPi) {
  for (Real ratio : {1.5, 2.5, 3.0, 100.0})
    for (Real u : {kPi / 2, -kPi / 2})
      for (FluidSide side : {FluidSide::Inside, FluidSide::Outside})
        for (int k = 0; k <= 20; ++k) {
          const Real s = -(side == FluidSide::Inside ? 1.0 : 0.4) * k / 20.0;
          const MapResult t = torus_map(s, 1, ratio, std::cos(u), side), cyl = cylinder_map(s, 1, side);
          ASSERT_TRUE(t.ok() && cyl.ok());
          EXPECT_NEAR(t.psi, cyl.psi, 1e-15) << "R/a = " << ratio << " s = " << s;
        }
}

// seed 004, Appendix B (eqs. 53-54): at R/a = 2, u = pi the torus map is the mirror. At s = -a
// the ghost lands exactly on the axis, a double root of the cubic (condition number ~1/sqrt(eps)),
// so the round-off bound there is sqrt(eps) ~ 1.5e-8; for s >= -0.9a it is ~1e-15.
TEST(GhostMaps, TorusEqualsMirrorAtAspectRatioTwo) {
  for (int k = 0; k <= 90; ++k) {
    const Real s = -0.01 * k;
    const MapResult t = torus_map(s, 1, 2, std::cos(kPi), FluidSide::Inside);
    ASSERT_TRUE(t.ok()) << "s = " << s;
    EXPECT_NEAR(t.psi, -s, 4e-15) << "s = " << s;
  }
  const MapResult edge = torus_map(-1 + 1e-12, 1, 2, -1, FluidSide::Inside);
  ASSERT_TRUE(edge.ok());
  EXPECT_NEAR(edge.psi, 1.0, 3e-8);
}

// The fast cubic root agrees with Viete's closed form over its whole range of use.
TEST(GhostMaps, FastCubicRootEqualsVieteForm) {
  for (int k = -1000; k <= 1000; ++k) {
    const Real kk = kTorusFastK * k / 1000.0;
    const Real z = depressed_cubic_root(kk), zf = depressed_cubic_root_fast(kk);
    EXPECT_NEAR(z * z * z - z, kk, 3 * 2.2e-16 * z * z * z + 2.2e-16 * z);  // rounding of z^3 - z
    EXPECT_NEAR(zf, z, 4 * 2.2e-16 * z) << "k = " << kk;  // Viete: rounding of acos, cos (ulps)
  }
  // continuity through the change of form at k = 2/(3 sqrt 3) and the fold at -2/(3 sqrt 3)
  const Real kc = 2 / (3 * std::sqrt(3.0));
  EXPECT_NEAR(depressed_cubic_root(kc * (1 + 1e-12)), depressed_cubic_root(kc * (1 - 1e-12)), 1e-10);
  EXPECT_NEAR(depressed_cubic_root(kCubicFoldK), 1 / std::sqrt(3.0), 1e-7);
}

// The sphere's cube root (guess + Halley) equals std::cbrt to round-off on its range [1, 2].
TEST(GhostMaps, FastCubeRootEqualsCbrt) {
  for (int k = 0; k <= 10000; ++k) {
    const Real y = 1 + k / 10000.0;
    // last Halley step rounds twice, std::cbrt is within 1 ulp: 3 ulp
    EXPECT_NEAR(cbrt_1_2(y), std::cbrt(y), 3 * std::numeric_limits<Real>::epsilon() * std::cbrt(y)) << "y = " << y;
  }
}

// Maps that leave their valid range report it (and return the limit, not NaN).
TEST(GhostMaps, OutOfRangeIsReported) {
  // torus R/a = 1.9 near the hole: the mirror image of the tube centre lies past the axis
  const MapResult t = torus_map(-0.99, 1, 1.9, -1, FluidSide::Inside);
  EXPECT_EQ(t.status, MapStatus::BeyondAxis);
  EXPECT_TRUE(std::isfinite(t.psi));
  EXPECT_TRUE(torus_map(-0.5, 1, 1.9, -1, FluidSide::Inside).ok());
  // obstacle: (R - s)^2 > 2 R^2 for -s > (sqrt2 - 1) R: not enough room inside the cylinder
  EXPECT_EQ(cylinder_map(-0.42, 1, FluidSide::Outside).status, MapStatus::NoRealSolution);
  EXPECT_TRUE(cylinder_map(-0.41, 1, FluidSide::Outside).ok());
  EXPECT_EQ(sphere_map(-0.27, 1, FluidSide::Outside).status, MapStatus::NoRealSolution);
  EXPECT_EQ(generic_wall_map(Cylinder<3>{Vec<3>::Zero(), 1, FluidSide::Outside}, -0.42, 0, 0).status,
            MapStatus::NoRealSolution);
  EXPECT_EQ(generic_wall_map(Torus{Vec<3>::Zero(), 1.9, 1, FluidSide::Inside}, -0.99, kPi, 0).status,
            MapStatus::NoRealSolution);
  // torus, fluid outside: the ghost must not pass the tube's centre line
  EXPECT_EQ(torus_map(-0.5, 1, 3, 1, FluidSide::Outside).status, MapStatus::NoRealSolution);
}

// Below R/a = 2 the limit of a valid map is the fold of the cubic: s* with 2g(a) - g(a+s*) = g_max.
TEST(GhostMaps, TorusBranchLimitBelowAspectRatioTwo) {
  const Real R = 1.99, Bu = -1 / R;
  const auto g = [&](Real x) { return x * x * (Bu * x / 3 + 0.5); };
  const Real gmax = g(R);  // g' = x (1 + Bu x) = 0 at x = R: the ghost on the axis
  Real lo = -1, hi = 0;    // bisection for 2 g(1) - g(1 + s) = gmax
  for (int i = 0; i < 200; ++i) {
    const Real m = 0.5 * (lo + hi);
    (2 * g(1) - g(1 + m) > gmax ? lo : hi) = m;
  }
  EXPECT_TRUE(torus_map(hi + 1e-9, 1, R, -1, FluidSide::Inside).ok());
  EXPECT_EQ(torus_map(lo - 1e-9, 1, R, -1, FluidSide::Inside).status, MapStatus::BeyondAxis);
}
