// The steppers' stop poll and step floor (StepperOptions::interrupt, ::step_floor):
//  - polling changes nothing: a run polled at every RHS evaluation and never interrupted is bit
//    for bit the run without a poll (state, time and every count), for every kind of stepper;
//  - an interrupt ends advance() at once (no RHS evaluation after the poll said stop) with the
//    last accepted step, and a later advance() continues: the leapfrog bit for bit, ARKODE to
//    its tolerance;
//  - a step that does not advance t fails at once, 100 steps in a row below the floor fail.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>

#include "../support/bit_equal.hpp"
#include "../integrate/test_systems.hpp"

namespace sphark::test {
namespace {

// Counts RHS evaluations; optionally a CFL-like max_stable_dt.
class Counted : public Kepler {
 public:
  explicit Counted(Real stable_dt = std::numeric_limits<Real>::infinity()) : Kepler(0.3), stable_(stable_dt) {}
  int rhs(Real t, const Real* y, Real* ydot) override {
    ++evaluations;
    return Kepler::rhs(t, y, ydot);
  }
  Real max_stable_dt(Real, const Real*, const Real*) override { return stable_; }
  long evaluations = 0;

 private:
  Real stable_;
};

struct Trajectory {
  std::vector<std::vector<Real>> states;
  std::vector<Real> times;
  StepperStats stats;
  long polls = 0;
};

Trajectory integrate(StepperOptions o, bool poll, Real stable_dt) {
  Counted sys(stable_dt);
  Trajectory tr;
  if (poll) o.interrupt = [&tr] { return ++tr.polls < 0; };  // asked, never stops
  const std::vector<Real> y0 = sys.exact(0);
  auto stepper = make_stepper(sys, o, 0, y0.data());
  std::vector<Real> y(4);
  Real t = 0;
  for (int k = 1; k <= 10; ++k) {
    EXPECT_EQ(stepper->advance(0.5 * k, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
    tr.states.push_back(y);
    tr.times.push_back(t);
  }
  tr.stats = stepper->stats();
  return tr;
}

struct Case {
  std::string name;
  StepperOptions options;
  Real stable_dt = std::numeric_limits<Real>::infinity();
};

std::vector<Case> cases() {
  StepperOptions imex = options("ark-imex", 1e-6);
  return {{"DP45 adaptive", options("ARKODE_DORMAND_PRINCE_7_4_5", 1e-8)},
          {"BS23 adaptive, capped", options("ARKODE_BOGACKI_SHAMPINE_4_2_3", 1e-6), 0.02},
          {"Verner fixed dt", options("ARKODE_VERNER_8_5_6", 1e-6, 0.01)},
          {"leapfrog fixed dt", options("leapfrog", 1e-6, 0.001)},
          {"leapfrog CFL", options("leapfrog"), 0.002},
          {"leapfrog-rev fixed dt", options("leapfrog-rev", 1e-6, 0.002)}};
}

}  // namespace

TEST(StepperInterrupt, PollingDoesNotChangeAnUninterruptedRun) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const Trajectory a = integrate(c.options, false, c.stable_dt), b = integrate(c.options, true, c.stable_dt);
    ASSERT_EQ(a.states.size(), b.states.size());
    for (std::size_t k = 0; k < a.states.size(); ++k) {
      EXPECT_TRUE(bit_equal(a.states[k], b.states[k])) << "output " << k;
      EXPECT_EQ(a.times[k], b.times[k]);
    }
    EXPECT_EQ(a.stats.steps, b.stats.steps);
    EXPECT_EQ(a.stats.attempts, b.stats.attempts);
    EXPECT_EQ(a.stats.rhs_evals, b.stats.rhs_evals);
    EXPECT_EQ(a.stats.last_dt, b.stats.last_dt);
    EXPECT_GE(b.polls, b.stats.steps);  // asked at least once per step
    std::printf("%-24s steps %ld, rhs %ld, polls %ld: bit-identical\n", c.name.c_str(), b.stats.steps, b.stats.rhs_evals,
                b.polls);
  }
}

// IMEX (ARKStep) too: the stiff damped oscillator.
TEST(StepperInterrupt, PollingDoesNotChangeAnImexRun) {
  struct Run {
    std::vector<Real> y;
    StepperStats stats;
    long polls = 0;
  };
  const auto run = [](bool poll) {
    DampedOscillator sys(1e4);
    StepperOptions o = options("ark-imex", 1e-6);
    Run r;
    if (poll) o.interrupt = [&r] { return ++r.polls < 0; };
    const Real y0[3] = {1, 0, sys.psi(0)};
    auto stepper = make_stepper(sys, o, 0, y0);
    r.y.resize(3);
    Real t = 0;
    EXPECT_EQ(stepper->advance(2.0, r.y.data(), t), AdvanceStatus::Reached);
    r.stats = stepper->stats();
    return r;
  };
  const Run a = run(false), b = run(true);
  EXPECT_TRUE(bit_equal(a.y, b.y));
  EXPECT_EQ(a.stats.steps, b.stats.steps);
  EXPECT_EQ(a.stats.rhs_evals, b.stats.rhs_evals);
  EXPECT_EQ(a.stats.rhs_evals_implicit, b.stats.rhs_evals_implicit);
  EXPECT_EQ(b.polls, b.stats.rhs_evals);  // one poll per explicit RHS evaluation
}

TEST(StepperInterrupt, StopsAtTheLastAcceptedStepAndContinuesLater) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const Trajectory whole = integrate(c.options, false, c.stable_dt);
    Counted sys(c.stable_dt);
    StepperOptions o = c.options;
    long polls = 0, evaluations_at_stop = -1;
    o.interrupt = [&] {
      if (++polls < 200) return false;
      if (evaluations_at_stop < 0) evaluations_at_stop = sys.evaluations;
      return true;
    };
    const std::vector<Real> y0 = sys.exact(0);
    auto stepper = make_stepper(sys, o, 0, y0.data());
    std::vector<Real> y(4);
    Real t = 0;
    ASSERT_EQ(stepper->advance(5.0, y.data(), t), AdvanceStatus::Interrupted);
    EXPECT_EQ(sys.evaluations, evaluations_at_stop);  // nothing evaluated after the poll said stop
    EXPECT_GT(t, 0);
    EXPECT_LT(t, 5.0);
    EXPECT_EQ(stepper->stats().current_time, t);
    const Real t_stop = t;
    const std::vector<Real> exact = sys.exact(t);  // a genuine step of the method at t
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(y[k], exact[k], 1e-3) << k;
    // the stop is over: continue through the same output times
    polls = -1000000000;
    for (std::size_t k = 0; k < whole.times.size(); ++k) {
      if (whole.times[k] <= t) continue;
      ASSERT_EQ(stepper->advance(whole.times[k], y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
      const bool leapfrog = c.options.method.rfind("leapfrog", 0) == 0;
      if (leapfrog) {
        EXPECT_TRUE(bit_equal(y, whole.states[k])) << "output " << k;
      }
      const std::vector<Real> e = sys.exact(t);
      for (int i = 0; i < 4; ++i) EXPECT_NEAR(y[i], e[i], 1e-3) << "output " << k;
    }
    std::printf("%-24s interrupted at poll 200 (t = %.6g), continued to t = %g\n", c.name.c_str(), t_stop, t);
  }
}

TEST(StepFloor, AStepThatDoesNotAdvanceTFailsAtOnce) {
  for (const std::string& method : {std::string("ARKODE_BOGACKI_SHAMPINE_4_2_3"), std::string("leapfrog")}) {
    SCOPED_TRACE(method);
    Oscillator sys;
    const Real y0[2] = {1, 0};
    const Real t0 = 1e6;  // 1e6 + 1e-12 == 1e6
    auto stepper = make_stepper(sys, options(method, 1e-6, 1e-12), t0, y0);
    Real y[2], t = 0;
    EXPECT_EQ(stepper->advance(t0 + 1, y, t), AdvanceStatus::Failed);
    EXPECT_EQ(t, t0);
    EXPECT_EQ(stepper->stats().steps, 0);
    EXPECT_NE(stepper->failure_reason().find("does not advance t (t + dt == t)"), std::string::npos)
        << stepper->failure_reason();
  }
}

TEST(StepFloor, HundredStepsInARowBelowTheFloorFailWithTheStateBefore) {
  const std::vector<std::pair<std::string, StepperOptions>> runs = {
      {"ERK fixed dt 1e-12", options("ARKODE_BOGACKI_SHAMPINE_4_2_3", 1e-6, 1e-12)},
      {"leapfrog fixed dt 1e-12", options("leapfrog", 1e-6, 1e-12)},
      {"leapfrog CFL 1e-12", options("leapfrog")},
      {"ERK adaptive, cap 1e-12", options("ARKODE_BOGACKI_SHAMPINE_4_2_3", 1e-6)}};
  for (auto [name, o] : runs) {
    SCOPED_TRACE(name);
    Counted sys(1e-12);
    o.step_floor = 1e-9;
    const std::vector<Real> y0 = sys.exact(0);
    auto stepper = make_stepper(sys, o, 0, y0.data());
    std::vector<Real> y(4);
    Real t = 0;
    EXPECT_EQ(stepper->advance(1.0, y.data(), t), AdvanceStatus::Failed);
    const std::string why = stepper->failure_reason();
    EXPECT_NE(why.find("100 steps in a row below the step floor"), std::string::npos) << why;
    EXPECT_EQ(stepper->stats().steps, kStepsBelowFloor - 1) << why;
    EXPECT_GT(t, 0);
    EXPECT_LE(t, 100e-12);
    std::printf("%-26s %s\n", name.c_str(), why.c_str());
  }
  // a step landing on an output time does not count, however short: 150 slivers of 1e-12
  for (const std::string& method : {std::string("leapfrog"), std::string("ARKODE_BOGACKI_SHAMPINE_4_2_3")}) {
    Counted sys;
    StepperOptions o = options(method, 1e-6, 0.1);
    o.step_floor = 1e-9;
    const std::vector<Real> y0 = sys.exact(0);
    auto stepper = make_stepper(sys, o, 0, y0.data());
    std::vector<Real> y(4);
    Real t = 0;
    for (int k = 1; k <= 150; ++k) {
      ASSERT_EQ(stepper->advance(0.1 * k, y.data(), t), AdvanceStatus::Reached) << method << stepper->failure_reason();
      ASSERT_EQ(stepper->advance(0.1 * k + 1e-12, y.data(), t), AdvanceStatus::Reached) << method << stepper->failure_reason();
    }
  }
}

}  // namespace sphark::test
