// The steps of a run's first line (run/cost_estimate.hpp, estimate_time): from the stable step,
// and never fewer than the diagnostics rows the time loop lands on.
#include <gtest/gtest.h>

#include "sphark/integrate/ode_system.hpp"
#include "sphark/run/cost_estimate.hpp"

using namespace sphark;

namespace {
// x' = 0 with a stable step of 1/64 (powers of two: the step counts are exact).
class StableStep : public OdeSystem {
 public:
  std::size_t size() const override { return 1; }
  int rhs(Real, const Real*, Real* ydot) override {
    ydot[0] = 0;
    return 0;
  }
  Real max_stable_dt(Real, const Real*, const Real*) override { return 1.0 / 64; }
};

CostEstimate estimate(const StepperOptions& so, Real longest_step) {
  StableStep system;
  const Real y0 = 0;
  CostEstimate e;
  estimate_time(e, system, so, 0, &y0, 1.0, longest_step, ProbeMeasurement{});
  return e;
}
}  // namespace

TEST(CostEstimate, StepsFromTheStableStepOrTheRowsWhicheverIsMore) {
  StepperOptions leapfrog;
  leapfrog.method = "leapfrog";
  leapfrog.cfl_safety = 0.5;
  EXPECT_EQ(estimate(leapfrog, 0).steps, 128);  // t_end / (0.5 / 64)
  EXPECT_FALSE(estimate(leapfrog, 0).steps_at_least);
  EXPECT_EQ(estimate(leapfrog, 0.125).steps, 128);  // rows every 1/8: the stable step is shorter
  EXPECT_FALSE(estimate(leapfrog, 0.125).steps_at_least);
  EXPECT_EQ(estimate(leapfrog, 1.0 / 1024).steps, 1024);  // rows every 1/1024 bound every step
  EXPECT_TRUE(estimate(leapfrog, 1.0 / 1024).steps_at_least);
  EXPECT_EQ(estimate(leapfrog, 1.0 / 1024).first_step, 1.0 / 1024);

  StepperOptions uncapped;  // an uncapped ERK run: 32 stable steps, an estimate of its reach
  uncapped.cap_by_stability = false;
  EXPECT_EQ(estimate(uncapped, 0).steps, 2);  // 1 / (32 / 64)
  EXPECT_EQ(estimate(uncapped, 1.0 / 64).steps, 64);  // the water drop's case: the rows bind
  EXPECT_TRUE(estimate(uncapped, 1.0 / 64).steps_at_least);
}
