// Recoverable and fatal RHS failures, exceptions, and option validation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "test_systems.hpp"

namespace sphark::test {
namespace {

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The RHS refuses stages more than `jump` ahead of the latest accepted evaluation (+1):
// the stepper restarts with smaller steps and still reaches t = 10 accurately.
void expect_recovery(StepperOptions opts, Real jump, Real tolerance) {
  JumpLimitedOscillator sys(jump);
  const Real y0[2] = {1, 0};
  auto stepper = make_stepper(sys, opts, 0, y0);
  Real y[2], t = 0;
  ASSERT_EQ(stepper->advance(10.0, y, t), AdvanceStatus::Reached) << stepper->failure_reason();
  const StepperStats st = stepper->stats();
  std::printf("%-45s %s, error %.2e\n", describe(opts).substr(0, 45).c_str(), format_stats(st).c_str(),
              std::abs(y[0] - std::cos(10.0)));
  EXPECT_GT(st.rhs_recoveries, 0);
  EXPECT_NEAR(y[0], std::cos(10.0), tolerance);
  EXPECT_NEAR(y[1], -std::sin(10.0), tolerance);
}

TEST(RecoverableFailure, ErkAdaptiveRestartsWithSmallerStep) {
  expect_recovery(options("ARKODE_DORMAND_PRINCE_7_4_5", 1e-8), 0.01, 1e-6);
}
TEST(RecoverableFailure, ErkFixedStepRestartsWithSmallerStep) {
  expect_recovery(options("ARKODE_DORMAND_PRINCE_7_4_5", 1e-8, 0.5), 0.06, 1e-6);
}
TEST(RecoverableFailure, ImexRestartsWithSmallerStep) { expect_recovery(options("ark-imex", 1e-8), 0.01, 1e-6); }
TEST(RecoverableFailure, LeapfrogHalvesTheStep) { expect_recovery(options("leapfrog", 1e-6, 0.1), 0.06, 2e-3); }

// The RHS fails fatally (-1) after t = 0.5: Failed, state and time of the last good step, and
// a reason naming the flag, the time and the system's own message.
void expect_fatal(const std::string& method, bool throwing_reason) {
  FailingOscillator sys(0.5, throwing_reason);
  const Real y0[2] = {1, 0};
  auto stepper = make_stepper(sys, options(method, 1e-6, method == "leapfrog" ? 0.01 : 0), 0, y0);
  Real y[2], t = 0;
  ASSERT_EQ(stepper->advance(1.0, y, t), AdvanceStatus::Failed) << method;
  const std::string reason = stepper->failure_reason();
  std::printf("%s: %s\n", method.c_str(), reason.c_str());
  EXPECT_LE(t, 0.5);
  EXPECT_GT(t, 0.3);
  EXPECT_NEAR(y[0], std::cos(t), 1e-4);  // a genuine state at t
  EXPECT_TRUE(contains(reason, throwing_reason ? "last_error exploded" : "density became negative")) << reason;
  EXPECT_TRUE(contains(reason, "rhs")) << reason;
  if (method != "leapfrog") {
    EXPECT_TRUE(contains(reason, "ARK_RHSFUNC_FAIL")) << reason;
  }
  // Failed is final.
  EXPECT_EQ(stepper->advance(2.0, y, t), AdvanceStatus::Failed);
}

TEST(FatalFailure, ErkReportsReason) { expect_fatal("ARKODE_DORMAND_PRINCE_7_4_5", false); }
TEST(FatalFailure, ImexReportsReason) { expect_fatal("ark-imex", false); }
TEST(FatalFailure, LeapfrogReportsReason) { expect_fatal("leapfrog", false); }

// Everything a C callback calls is guarded: here last_error() throws while a failure is being
// recorded.
TEST(Exceptions, NoExceptionEscapesACallback) {
  for (const char* method : {"ARKODE_DORMAND_PRINCE_7_4_5", "ark-imex", "leapfrog"}) expect_fatal(method, true);
}

TEST(Options, BadInputIsRejectedWithOneLineNamingTheOption) {
  Oscillator sys;
  const Real y0[2] = {1, 0};
  auto message = [&](StepperOptions o) -> std::string {
    try {
      make_stepper(sys, o, 0, y0);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_TRUE(contains(message(options("RK4")), "method=RK4"));
  EXPECT_TRUE(contains(message(options("ARKODE_KNOTH_WOLKE_3_3")), "method=ARKODE_KNOTH_WOLKE_3_3"));
  EXPECT_EQ(message(options("ARKODE_KNOTH_WOLKE_3_3", 1e-6, 0.1)), "");  // fixed step is fine
  EXPECT_TRUE(contains(message(options("ARKODE_HEUN_EULER_2_1_2", -1)), "rtol=-1"));
  StepperOptions o = options("ARKODE_HEUN_EULER_2_1_2");
  o.atol = {1e-6, 1e-6, 1e-6};
  EXPECT_TRUE(contains(message(o), "atol=3 values"));
  o = options("ark-imex");
  EXPECT_TRUE(contains(message(o), "method=ark-imex"));
  EXPECT_TRUE(contains(message(options("leapfrog")), "method=leapfrog"));  // no step-size limit
  FallingBall ball;
  struct NoPositions : Oscillator {
    std::size_t position_size() const override { return 0; }
  } nopos;
  EXPECT_THROW(make_stepper(nopos, options("leapfrog", 1e-6, 0.1), 0, y0), std::invalid_argument);
  JumpLimitedOscillator stiff(1);
  o = options("ark-imex");
  o.imex_table = "ARK999";
  EXPECT_THROW(make_stepper(stiff, o, 0, y0), std::invalid_argument);
  for (const auto& m : message(options("RK4"))) EXPECT_NE(m, '\n');
}

TEST(Options, DescribeAndFormatStatsAreOneLine) {
  for (const StepperOptions& o : {options("ARKODE_VERNER_8_5_6"), options("ark-imex", 1e-6, 0.1), options("leapfrog")}) {
    const std::string d = describe(o);
    EXPECT_EQ(d.find('\n'), std::string::npos);
    EXPECT_TRUE(contains(d, o.method == "ark-imex" ? "ARK436L2SA" : o.method)) << d;
  }
  StepperStats st;
  st.steps = 12;
  st.rhs_evals = 73;
  const std::string s = format_stats(st);
  EXPECT_TRUE(contains(s, "steps=12") && contains(s, "rhs_evals=73")) << s;
  EXPECT_EQ(s.find('\n'), std::string::npos);
}

}  // namespace
}  // namespace sphark::test

namespace sphark::test {
namespace {
// max_stable_dt fails (NaN, the documented failure value) from t = 0.5 on.
struct FailingStableStep : Oscillator {
  Real max_stable_dt(Real t, const Real*, const Real*) override {
    return t < 0.5 ? 0.05 : std::numeric_limits<Real>::quiet_NaN();
  }
  std::string last_error() const override { return "no sound speed"; }
};
}  // namespace

// A failing max_stable_dt stops the run (the step is never taken uncapped): adaptive ERK at the
// start of the next output interval, the leapfrog at the next step; the reason names it.
TEST(StableStepFailure, NaNStopsAdaptiveAndLeapfrogRuns) {
  for (const char* method : {"ARKODE_DORMAND_PRINCE_7_4_5", "leapfrog"}) {
    SCOPED_TRACE(method);
    FailingStableStep sys;
    const Real y0[2] = {1, 0};
    auto stepper = make_stepper(sys, options(method, 1e-6), 0, y0);
    Real y[2], t = 0;
    AdvanceStatus st = AdvanceStatus::Reached;
    for (int k = 1; k <= 10 && st == AdvanceStatus::Reached; ++k) st = stepper->advance(0.1 * k, y, t);
    ASSERT_EQ(st, AdvanceStatus::Failed);
    EXPECT_GE(t, 0.5 - 1e-12);
    EXPECT_LT(t, 0.6);
    EXPECT_TRUE(contains(stepper->failure_reason(), "max_stable_dt")) << stepper->failure_reason();
    EXPECT_TRUE(contains(stepper->failure_reason(), "no sound speed")) << stepper->failure_reason();
  }
}
}  // namespace sphark::test

namespace sphark::test {
namespace {
// rhs() throws from t = 0.5 on: a scheme need not catch, the stepper's net does (the one net).
struct ThrowingOscillator : Oscillator {
  int rhs(Real t, const Real* y, Real* ydot) override {
    if (t >= 0.5) throw std::runtime_error("neighbour build failed");
    return Oscillator::rhs(t, y, ydot);
  }
  bool has_stiff_diagonal() const override { return true; }
  int stiff_diagonal(Real, const Real*, Real* c) override { return c[0] = c[1] = 0, 0; }
};
}  // namespace

TEST(Exceptions, AThrowingRhsEndsTheRunAsAFatalFailureWithItsMessage) {
  for (const char* method : {"ARKODE_DORMAND_PRINCE_7_4_5", "ark-imex", "leapfrog"}) {
    SCOPED_TRACE(method);
    ThrowingOscillator sys;
    const Real y0[2] = {1, 0};
    auto stepper = make_stepper(sys, options(method, 1e-6, std::string(method) == "leapfrog" ? 0.01 : 0.0), 0, y0);
    Real y[2], t = 0;
    EXPECT_EQ(stepper->advance(1.0, y, t), AdvanceStatus::Failed);
    EXPECT_LT(t, 0.5);
    EXPECT_TRUE(contains(stepper->failure_reason(), "neighbour build failed")) << stepper->failure_reason();
  }
}
}  // namespace sphark::test
