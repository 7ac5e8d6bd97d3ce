// A particle aimed at the wall is reflected by its own ghost (seed 004 §2, free slip): the ghost
// lies on the particle's normal line, so the force is radial, angular momentum about the centre
// is conserved exactly and the motion is a 1D conservative problem in r. Back at its starting
// radius the particle has its normal velocity reversed and its tangential velocity kept.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "lattice_helpers.hpp"

namespace sphark {
namespace {

struct Bounce {
  Real vr_in, vt_in, vr_out, vt_out, r_min, max_dL;
};

Bounce bounce(GhostMap map, VelocityBc bc) {
  LatticeParams p = lattice_test::undriven(map);
  p.velocity = bc;
  p.mass = 1;
  p.eta = 1.0;  // one neighbour (the ghost) at q* = d/h with W(0) + W(q*) = eta^2 / h^2 (2D)
  p.sound_speed = 1;
  const Real r0 = 0.25;
  const std::vector<Real> x0{r0, 0};
  const Vec<2> v0(-1.0, 0.3);  // radial -1 (towards the wall), tangential 0.3
  {  // rho0 := the particle's density at the start, so that P = 0 there and P > 0 closer in
    LatticeSystem probe(1, p);
    const auto y = lattice_test::state(probe, x0, v0);
    EXPECT_EQ(probe.prepare(y.data()), 0) << probe.last_error();
    EXPECT_EQ(probe.ghost_count(), 1u);
    p.rho0 = probe.density()[0];
  }
  LatticeSystem sys(1, p);
  std::vector<Real> y = lattice_test::state(sys, x0, v0), f(y.size()), prev;
  const Real dt = 2e-5;
  const Real L0 = x0[0] * v0[1] - x0[1] * v0[0];
  Bounce b{-1.0, 0.3, 0, 0, r0, 0};
  EXPECT_EQ(sys.rhs(0, y.data(), f.data()), 0) << sys.last_error();
  for (int step = 0; step < 200000; ++step) {  // kick-drift-kick
    prev = y;
    for (int k = 0; k < 2; ++k) y[2 + k] += 0.5 * dt * f[2 + k];
    for (int k = 0; k < 2; ++k) y[k] += dt * y[2 + k];
    EXPECT_EQ(sys.rhs(0, y.data(), f.data()), 0) << sys.last_error();
    for (int k = 0; k < 2; ++k) y[2 + k] += 0.5 * dt * f[2 + k];
    const Real r = std::hypot(y[0], y[1]);
    b.r_min = std::min(b.r_min, r);
    b.max_dL = std::max(b.max_dL, std::abs(y[0] * y[3] - y[1] * y[2] - L0));
    if (r >= r0 && b.r_min < r0) {  // back at r0: interpolate the radial and tangential velocity
      const Real rp = std::hypot(prev[0], prev[1]), w = (r0 - rp) / (r - rp);
      auto vel = [&](const std::vector<Real>& z) {
        const Real rr = std::hypot(z[0], z[1]);
        const Vec<2> e(z[0] / rr, z[1] / rr);
        return Vec<2>(z[2] * e[0] + z[3] * e[1], -z[2] * e[1] + z[3] * e[0]);
      };
      const Vec<2> v = (1 - w) * vel(prev) + w * vel(y);
      b.vr_out = v[0];
      b.vt_out = v[1];
      return b;
    }
  }
  ADD_FAILURE() << "the particle did not come back to r0";
  return b;
}

TEST(LatticeReflection, FreeSlipReversesNormalVelocityAndKeepsTangential) {
  for (GhostMap map : {GhostMap::Mirror, GhostMap::DensityPreserving}) {
    const Bounce b = bounce(map, VelocityBc::FreeSlip);
    std::printf("[ %s ] closest approach r = %.5f (R = 0.2); v_r %.6f -> %.6f, v_t %.6f -> %.6f, max |dL| %.2e\n",
                map_name(map).c_str(), b.r_min, b.vr_in, b.vr_out, b.vt_in, b.vt_out, b.max_dL);
    EXPECT_GT(b.r_min, 0.2) << "no penetration";
    EXPECT_LT(b.r_min, 0.24) << "the wall acted";
    EXPECT_NEAR(b.vr_out, -b.vr_in, 1e-4);  // elastic: O(dt^2) of the leapfrog
    EXPECT_NEAR(b.vt_out, b.vt_in, 1e-4);
    EXPECT_LT(b.max_dL, 1e-12);  // central force: angular momentum to round-off
  }
}

TEST(LatticeReflection, GhostVelocityIsMirroredForFreeSlipAndReversedForNoSlip) {
  for (VelocityBc bc : {VelocityBc::FreeSlip, VelocityBc::NoSlip}) {
    LatticeParams p = lattice_test::undriven(GhostMap::Mirror);
    p.velocity = bc;
    p.mass = 1;
    p.eta = 1.0;
    LatticeSystem sys(1, p);
    const auto y = lattice_test::state(sys, {0.0, 0.25}, Vec<2>(0.3, -1.0));  // normal is -y here
    ASSERT_EQ(sys.prepare(y.data()), 0) << sys.last_error();
    ASSERT_EQ(sys.ghost_count(), 1u);
    const Real* vg = sys.ghosts().velocities();
    EXPECT_DOUBLE_EQ(vg[1], 1.0);  // normal component reversed
    EXPECT_DOUBLE_EQ(vg[0], bc == VelocityBc::FreeSlip ? 0.3 : -0.3);
    EXPECT_NEAR(sys.all_positions()[3], 0.15, 1e-15);  // mirror: s' = -s
  }
}

}  // namespace
}  // namespace sphark
