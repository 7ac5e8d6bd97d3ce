// Root finding: a ball falling from x = 1 under x'' = -1 hits x = 0 at t = sqrt(2).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "test_systems.hpp"

namespace sphark::test {
namespace {

void expect_root_at_sqrt2(const StepperOptions& opts) {
  FallingBall sys;
  const Real y0[2] = {1, 0};
  auto stepper = make_stepper(sys, opts, 0, y0);
  Real y[2], t = 0;
  ASSERT_EQ(stepper->advance(2.0, y, t), AdvanceStatus::RootFound) << describe(opts);
  std::printf("%-40s root at t = %.15f (error %.2e), x = %.2e\n", describe(opts).substr(0, 40).c_str(), t,
              t - std::sqrt(2.0), y[0]);
  EXPECT_NEAR(t, std::sqrt(2.0), 1e-8) << describe(opts);
  EXPECT_NEAR(y[0], 0.0, 1e-8);
  EXPECT_NEAR(y[1], -t, 1e-8);  // the state returned is the state at the root
  ASSERT_EQ(stepper->roots_found().size(), 1u);
  EXPECT_EQ(stepper->roots_found()[0], -1);  // g = x decreasing
  // Continue past the root: no second root, reach t = 2 with x = 1 - 2 = -1.
  ASSERT_EQ(stepper->advance(2.0, y, t), AdvanceStatus::Reached) << describe(opts);
  EXPECT_EQ(t, 2.0);
  EXPECT_NEAR(y[0], -1.0, 1e-8);
  EXPECT_NEAR(y[1], -2.0, 1e-8);
  EXPECT_TRUE(stepper->roots_found().empty());
}

TEST(Roots, FallingBallErkAdaptive) { expect_root_at_sqrt2(options("ARKODE_DORMAND_PRINCE_7_4_5", 1e-8)); }
TEST(Roots, FallingBallErkFixedStep) { expect_root_at_sqrt2(options("ARKODE_BOGACKI_SHAMPINE_4_2_3", 1e-8, 0.1)); }
TEST(Roots, FallingBallImex) {
  // The falling ball has no stiff part; give it a zero one so that ark-imex accepts it.
  struct ZeroStiff : FallingBall {
    bool has_stiff_diagonal() const override { return true; }
    int stiff_diagonal(Real, const Real*, Real* c) override { return c[0] = c[1] = 0, 0; }
  };
  ZeroStiff sys;
  const Real y0[2] = {1, 0};
  auto stepper = make_stepper(sys, options("ark-imex", 1e-8), 0, y0);
  Real y[2], t = 0;
  ASSERT_EQ(stepper->advance(2.0, y, t), AdvanceStatus::RootFound);
  EXPECT_NEAR(t, std::sqrt(2.0), 1e-8);
}
// Leapfrog is exact for constant acceleration; the root is located on its trajectory.
TEST(Roots, FallingBallLeapfrog) { expect_root_at_sqrt2(options("leapfrog", 1e-6, 0.1)); }

// Repeated roots: g = (x, v) of the oscillator cross zero alternately every pi/2; every crossing
// is reported once, with its direction, and the run continues to t = 10.
void expect_oscillator_roots(const StepperOptions& opts, Real tolerance) {
  struct Both : Oscillator {
    int num_roots() const override { return 2; }
    int roots(Real, const Real* y, Real* g) noexcept override { return g[0] = y[0], g[1] = y[1], 0; }
  } sys;
  const Real y0[2] = {1, 0};
  auto stepper = make_stepper(sys, opts, 0, y0);
  Real y[2], t = 0;
  int found = 0;
  while (stepper->advance(10.0, y, t) == AdvanceStatus::RootFound) {
    ++found;  // k-th root at k pi/2: x crosses for odd k, v for even k (v starts at 0: not a crossing)
    EXPECT_NEAR(t, found * kPi / 2, tolerance) << describe(opts);
    const std::vector<int> r = stepper->roots_found();
    const int which = found % 2 == 1 ? 0 : 1;
    EXPECT_NE(r[which], 0) << "root " << found << " at t=" << t;
    EXPECT_EQ(r[1 - which], 0) << "root " << found << " at t=" << t;
    // x = cos t decreases through 0 at pi/2 + 2 pi m; v = -sin t increases through 0 at pi + 2 pi m
    const int expected = which == 0 ? (found % 4 == 1 ? -1 : 1) : (found % 4 == 2 ? 1 : -1);
    EXPECT_EQ(r[which], expected) << "root " << found;
    ASSERT_LT(found, 10);
  }
  EXPECT_EQ(t, 10.0);
  EXPECT_EQ(found, 6);  // 10 / (pi/2) = 6.4
}

TEST(Roots, OscillatorCrossingsErk) { expect_oscillator_roots(options("ARKODE_VERNER_8_5_6", 1e-10), 1e-8); }
TEST(Roots, OscillatorCrossingsLeapfrog) { expect_oscillator_roots(options("leapfrog", 1e-6, 0.01), 1e-4); }

}  // namespace
}  // namespace sphark::test
