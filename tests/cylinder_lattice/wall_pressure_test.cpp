// The background pressure of the lattice EOS (docs/cylinder_lattice.md, "Background pressure"): with the
// plain Tait EOS (seed 000, eq. 26) an under-dense particle next to the wall has P < 0 and its own
// ghost pulls it towards the wall; this is how a particle of the 10 000-particle nonlinear-map run
// crossed the wall at t = 4.51. With P_b = c_s^2 rho0 / 7 the pressure is never negative and the
// same ghost pushes the particle away from the wall.
#include <gtest/gtest.h>

#include <cmath>

#include "lattice_helpers.hpp"
#include "sphark/operators/tait_eos.hpp"

namespace sphark {
namespace {

// Radial acceleration and pressure of one particle at rest at distance `gap` from the wall, in a
// fluid whose rest density is twice the particle's density (strongly under-dense, P_Tait < 0).
struct Probe {
  Real radial_acceleration, pressure, rho0;
};

Probe underdense_particle(GhostMap map, Real background, Real gap) {
  LatticeParams p = lattice_test::undriven(map);
  p.mass = 1;
  p.eta = 1.0;
  p.sound_speed = 1;
  p.background = background;
  const std::vector<Real> x0{p.radius + gap, 0};
  {
    LatticeSystem probe(1, p);
    const auto y = lattice_test::state(probe, x0, Vec<2>::Zero());
    EXPECT_EQ(probe.prepare(y.data()), 0) << probe.last_error();
    EXPECT_EQ(probe.ghost_count(), 1u);
    p.rho0 = 2 * probe.density()[0];
  }
  LatticeSystem sys(1, p);
  const auto y = lattice_test::state(sys, x0, Vec<2>::Zero());
  std::vector<Real> f(y.size());
  EXPECT_EQ(sys.rhs(0, y.data(), f.data()), 0) << sys.last_error();
  EXPECT_DOUBLE_EQ(f[sys.velocity_offset() + 1], 0.0);  // the ghost lies on the normal line
  return {f[sys.velocity_offset()], sys.pressure()[0], p.rho0};
}

TEST(LatticeWallPressure, PlainTaitGhostAttractsAnUnderdenseParticleBackgroundPressureRepelsIt) {
  for (GhostMap map : {GhostMap::Mirror, GhostMap::DensityPreserving})
    for (Real gap : {0.005, 0.02, 0.05}) {
      const Probe plain = underdense_particle(map, 0, gap);
      const Probe background = underdense_particle(map, 1, gap);
      EXPECT_LT(plain.pressure, 0);
      EXPECT_LT(plain.radial_acceleration, 0) << "towards the wall";
      EXPECT_GT(background.pressure, 0);
      EXPECT_GT(background.radial_acceleration, 0) << "away from the wall";
      EXPECT_NEAR(background.pressure - plain.pressure, background.rho0 / 7, 1e-14);  // P_b = c_s^2 rho0 / 7, c_s = 1
    }
}

// P = Tait + P_b vanishes at rho = rho0 (1 - background)^(1/7) and is positive above it (the
// default 0.15: rho >= 0.977 rho0).
TEST(LatticeWallPressure, BackgroundPressureMovesTheZeroOfThePressureBelowRho0) {
  for (Real background : {0.15, 0.5, 0.9}) {
    LatticeParams p;
    p.background = background;
    const Real rho_zero = p.rho0 * std::pow(1 - background, 1.0 / 7);
    const Real B = p.sound_speed * p.sound_speed * p.rho0 / 7;
    EXPECT_NEAR(tait_pressure(rho_zero, p.rho0, p.sound_speed) + background_pressure(p), 0, 1e-14 * B);
    EXPECT_GT(tait_pressure(rho_zero + 1e-6 * p.rho0, p.rho0, p.sound_speed) + background_pressure(p), 0);
  }
  LatticeParams full;  // background 1: P = c_s^2 rho0 / 7 (rho / rho0)^7 >= 0 at every density
  full.background = 1;
  for (Real rho : {0.0, 0.01, 0.5, 0.9, 1.0, 1.1}) EXPECT_GE(tait_pressure(rho, 1, 5) + background_pressure(full), 0);
  EXPECT_NEAR(std::pow(1 - LatticeParams{}.background, 1.0 / 7), 0.977, 5e-4);  // the documented default
}

}  // namespace
}  // namespace sphark
