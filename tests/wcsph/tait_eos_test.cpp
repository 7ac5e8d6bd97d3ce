// The Tait equation of state (seed 000, eq. 26) and its specific internal energy: the energy is
// the integral of P / rho^2, so du/drho = P / rho^2 (checked against a Richardson-extrapolated
// central difference), u(rho0) = 0, and the density inverse round-trips.
#include <gtest/gtest.h>

#include <cmath>

#include "sphark/operators/tait_eos.hpp"

namespace sphark {
namespace {

TEST(TaitEos, PressureVanishesAtRestDensityAndInverts) {
  for (Real rho0 : {1.0, 1000.0})
    for (Real c : {5.0, 1400.0}) {
      EXPECT_EQ(tait_pressure(rho0, rho0, c), 0);
      for (Real s : {0.9, 0.99, 1.0, 1.02, 1.1}) {
        const Real P = tait_pressure(s * rho0, rho0, c);
        EXPECT_NEAR(tait_density(P, rho0, c), s * rho0, 1e-13 * rho0);
      }
      // c^2 = dP/drho: central difference of the pressure
      const Real rho = 1.03 * rho0, d = 1e-5 * rho0;
      const Real c_fd = std::sqrt((tait_pressure(rho + d, rho0, c) - tait_pressure(rho - d, rho0, c)) / (2 * d));
      EXPECT_NEAR(tait_sound_speed(rho, rho0, c), c_fd, 1e-8 * c);
    }
}

TEST(TaitEos, SpecificEnergyIsTheIntegralOfPOverRhoSquared) {
  const Real rho0 = 1, c = 5;
  for (Real background : {0.0, 25.0 / 7, 10.0}) {
    EXPECT_EQ(tait_specific_energy(rho0, rho0, c, background), 0);
    for (Real rho : {0.6, 0.95, 1.0, 1.05, 1.3}) {
      auto u = [&](Real r) { return tait_specific_energy(r, rho0, c, background); };
      auto fd = [&](Real d) { return (u(rho + d) - u(rho - d)) / (2 * d); };
      const Real slope = (4 * fd(1e-4) - fd(2e-4)) / 3;  // O(d^4)
      const Real P = tait_pressure(rho, rho0, c) + background;
      EXPECT_NEAR(slope, P / (rho * rho), 1e-8 * (1 + std::abs(P)));
    }
  }
}

}  // namespace
}  // namespace sphark
