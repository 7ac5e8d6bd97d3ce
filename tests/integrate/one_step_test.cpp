// Stepper::step: one step towards t_out, never past it. Stepping one by one to t_out reaches the
// same state bit for bit as advance() when the step bounds do not depend on the state (no
// max_stable_dt cap): adaptive Dormand-Prince, IMEX and the fixed-step leapfrog.
#include <gtest/gtest.h>

#include <cstring>

#include "test_systems.hpp"

namespace sphark::test {

TEST(OneStep, SteppingToTOutEqualsAdvanceBitForBit) {
  for (const char* method : {"ARKODE_DORMAND_PRINCE_7_4_5", "ark-imex", "leapfrog"}) {
    SCOPED_TRACE(method);
    const StepperOptions o = options(method, 1e-8, std::string(method) == "leapfrog" ? 0.01 : 0.0);
    DampedOscillator a(5), b(5);
    const Real y0[3] = {1, 0, 1};
    auto whole = make_stepper(a, o, 0, y0);
    auto single = make_stepper(b, o, 0, y0);
    Real ya[3], yb[3], ta = 0, tb = 0;
    ASSERT_EQ(whole->advance(2.0, ya, ta), AdvanceStatus::Reached);
    int calls = 0;
    AdvanceStatus st = AdvanceStatus::Stepped;
    while (st == AdvanceStatus::Stepped) {
      st = single->step(2.0, yb, tb);
      ++calls;
      ASSERT_LE(tb, 2.0);
    }
    ASSERT_EQ(st, AdvanceStatus::Reached);
    EXPECT_EQ(tb, 2.0);
    EXPECT_EQ(calls, single->stats().steps);  // one step per call
    EXPECT_EQ(single->stats().steps, whole->stats().steps);
    EXPECT_EQ(std::memcmp(ya, yb, sizeof ya), 0);
  }
}

}  // namespace sphark::test
