// MRIStep nested over three levels (StepperOptions::mri_levels, issue #17): the error falls at
// the coupling table's order as the slow step halves, every call evaluates exactly one level's
// set (or a wrapper's full RHS: its level and the deeper ones), a resize is bit for bit a fresh
// stepper, output stops change nothing, the adaptive levels, and the option errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "oscillator_ensemble.hpp"
#include "resize_check.hpp"
#include "switching_ensemble.hpp"
#include "sphark/integrate/stepper.hpp"

namespace sphark::test {
namespace {

// Three time scales: 4 oscillators at w = 1, 2 at 50, 2 at 900 (all-pairs springs kappa).
OscillatorEnsemble three_scales() { return OscillatorEnsemble({1, 1, 1, 1, 50, 50, 900, 900}, 0.3); }
const std::vector<std::size_t> kSlow{0, 1, 2, 3}, kMiddle{4, 5}, kFast{6, 7}, kMiddleAndFast{4, 5, 6, 7};

std::vector<Real> initial_state(const OscillatorEnsemble& sys, bool slow_manifold) {
  const std::vector<Real> y = excited_state(sys.n());
  return slow_manifold ? sys.project_below(y, 10) : y;
}

// Slow step h, level k steps by h / ratio^k: for 0.025 <= h <= 0.2 and ratio 20 the w = 50
// pair is on level 1 (1/50 < h, >= h/20) and the w = 900 pair on level 2 (1/900 < h/20).
StepperOptions nested(const std::string& table, Real h, int ratio = 20, int levels = 3) {
  StepperOptions o;
  o.method = "mri-" + table;
  o.fixed_dt = h;
  o.mri_ratio = ratio;
  o.mri_levels = levels;
  o.mri_fast_table = "ARKODE_DORMAND_PRINCE_7_4_5";
  return o;
}

std::vector<Real> run(OscillatorEnsemble& sys, const StepperOptions& o, const std::vector<Real>& y0, Real t_end,
                      StepperStats* stats = nullptr) {
  auto stepper = make_stepper(sys, o, 0, y0.data());
  std::vector<Real> y(y0.size());
  Real t = 0;
  EXPECT_EQ(stepper->advance(t_end, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
  if (stats) *stats = stepper->stats();
  return y;
}

void expect_order(const std::string& table, bool slow_manifold) {
  const Real h0 = 0.2;
  std::vector<Real> e;
  for (int k = 0; k < 4; ++k) {
    OscillatorEnsemble sys = three_scales();
    const std::vector<Real> y0 = initial_state(sys, slow_manifold);
    e.push_back(max_error(run(sys, nested(table, h0 / (1 << k)), y0, 1.0), sys.exact(y0, 1.0)));
  }
  const int p = mri_table_order(table);
  for (std::size_t k = 1; k < e.size(); ++k) {
    const Real order = std::log2(e[k - 1] / e[k]);
    std::printf("%s %s, 3 levels: error %.3e -> %.3e, order %.2f (table %d)\n", table.c_str(),
                slow_manifold ? "slow-manifold" : "excited", e[k - 1], e[k], order, p);
    EXPECT_GE(order, p - 0.3) << table << " halving " << k;
  }
}

// Four time scales and four levels, ratio 10: w = 1, 45, 450 and 4500; for 0.025 <= h <= 0.2,
// 1/w_k lies in [h/10^k, h/10^(k-1)): level k holds the k-th pair at every h. (ERK45a: orders
// 3.75, 3.90, then 2.60 at 2e-7; with ratio 20 and w = 1, 50, 900, 16200: 3.75, 3.91, 4.03, but
// 15 s, too long for the suite.)
TEST(MriNested, FourLevelsOrderAsTheSlowStepHalves) {
  for (const std::string table : {"ARKODE_MRI_GARK_ERK33a", "ARKODE_MIS_KW3"}) {
    std::vector<Real> e;
    for (int k = 0; k < 4; ++k) {
      OscillatorEnsemble sys({1, 1, 45, 45, 450, 450, 4500, 4500}, 0.3);
      const std::vector<Real> y0 = initial_state(sys, true);
      StepperStats s;
      e.push_back(max_error(run(sys, nested(table, 0.2 / (1 << k), 10, 4), y0, 1.0, &s), sys.exact(y0, 1.0)));
      EXPECT_EQ(s.levels.size(), 4u);
      for (int l = 0; l < 4; ++l) EXPECT_GT(s.levels[l].rhs_evals, 0) << "level " << l;  // every level evaluated
    }
    for (std::size_t k = 1; k < e.size(); ++k) {
      const Real order = std::log2(e[k - 1] / e[k]);
      std::printf("%s slow-manifold, 4 levels: error %.3e -> %.3e, order %.2f\n", table.c_str(), e[k - 1], e[k], order);
      EXPECT_GE(order, mri_table_order(table) - 0.3);
    }
  }
}

TEST(MriNested, Erk33aOrderAsTheSlowStepHalves) { expect_order("ARKODE_MRI_GARK_ERK33a", true); }
TEST(MriNested, Erk45aOrderAsTheSlowStepHalves) { expect_order("ARKODE_MRI_GARK_ERK45a", true); }
TEST(MriNested, MisKw3OrderAsTheSlowStepHalves) { expect_order("ARKODE_MIS_KW3", true); }
TEST(MriNested, Erk33aOrderExcited) { expect_order("ARKODE_MRI_GARK_ERK33a", false); }
// (ERK45a with the fast modes excited: 2.28 -> 8.97e-2 -> 5.52e-3 (orders 4.67, 4.02), then the
// fast DP5's floor, 1.75e-3 at h = 0.025; a two-level MRIStep with the same fast step has it too.)

TEST(MriNested, EachLevelEvaluatesExactlyItsSet) {
  for (const std::string& table : mri_table_names()) {
    OscillatorEnsemble sys = three_scales();
    sys.record_calls = true;
    const std::vector<Real> y0 = initial_state(sys, false);
    StepperStats s;
    run(sys, nested(table, 0.1), y0, 1.0, &s);
    ASSERT_EQ(s.levels.size(), 3u);
    std::printf("%s:", table.c_str());
    for (const LevelStats& l : s.levels) std::printf(" (steps %ld rhs %ld particles %ld)", l.steps, l.rhs_evals, l.particle_evals);
    std::printf("\n");
    long calls[4] = {0, 0, 0, 0};  // slow, middle, fast, middle + fast (the middle wrapper's full RHS)
    for (const auto& call : sys.calls) {
      const int which = call.active == kSlow ? 0 : call.active == kMiddle ? 1 : call.active == kFast ? 2
                        : call.active == kMiddleAndFast ? 3 : -1;
      EXPECT_GE(which, 0) << "a call with " << call.active.size() << " particles at t=" << call.t;
      if (which >= 0) ++calls[which];
    }
    EXPECT_EQ(calls[0], s.levels[0].rhs_evals);
    EXPECT_EQ(calls[1] + calls[3], s.levels[1].rhs_evals);
    EXPECT_EQ(calls[2], s.levels[2].rhs_evals);
    EXPECT_GT(calls[3], 0);
    EXPECT_EQ(s.levels[0].particle_evals, 4 * calls[0]);
    EXPECT_EQ(s.levels[1].particle_evals, 2 * calls[1] + 4 * calls[3]);
    EXPECT_EQ(s.levels[2].particle_evals, 2 * calls[2]);
    EXPECT_EQ(s.particle_evals, s.levels[0].particle_evals + s.levels[1].particle_evals + s.levels[2].particle_evals);
    EXPECT_EQ(s.steps, 10);  // 1.0 / 0.1
    EXPECT_GE(s.levels[1].steps, 10 * 20);  // at least ratio middle steps per slow step
    EXPECT_GE(s.levels[2].steps, 10 * 400);
    EXPECT_EQ(sys.full_calls, 0);
  }
}

// resize() (resize_check.hpp): every level's integrator and wrapper made afresh.
TEST(MriNested, ResizeStartsEveryLevelAfresh) {
  expect_resize_continues_as_fresh(three_scales, nested("ARKODE_MRI_GARK_ERK45a", 0.1), initial_state(three_scales(), false),
                                   0.5, 1.0, 10);
}

// Output times inside a run (advance to t1, then t2) change nothing: a slow step is one step of
// every level whatever the caller's stops, when they fall on slow steps.
TEST(MriNested, StoppingBetweenSlowStepsChangesNothing) {
  OscillatorEnsemble a_sys = three_scales(), b_sys = three_scales();
  const std::vector<Real> y0 = initial_state(a_sys, false);
  const StepperOptions o = nested("ARKODE_MRI_GARK_ERK33a", 0.1);
  auto a = make_stepper(a_sys, o, 0, y0.data()), b = make_stepper(b_sys, o, 0, y0.data());
  std::vector<Real> ya(y0.size()), yb(y0.size());
  Real ta = 0, tb = 0;
  for (int k = 1; k <= 10; ++k) ASSERT_EQ(a->advance(0.1 * k, ya.data(), ta), AdvanceStatus::Reached);
  ASSERT_EQ(b->advance(1.0, yb.data(), tb), AdvanceStatus::Reached);
  for (std::size_t k = 0; k < ya.size(); ++k) EXPECT_EQ(ya[k], yb[k]) << "entry " << k;
}

// Adaptive (max_dt): the power-of-two levels 0 (w = 1), 5 (w = 50: 1/50 >= 0.5/32) and 10
// (w = 900) are shared out as MRI levels 0, 1 (up to 0 + ceil(10/2) = 5) and 2; the steps are
// 0.5, 0.5/32 and 0.5/1024.
TEST(MriNested, AdaptiveLevelsShareThePowerOfTwoLevels) {
  OscillatorEnsemble sys = three_scales();
  sys.record_calls = true;
  const std::vector<Real> y0 = initial_state(sys, true);
  StepperOptions o = nested("ARKODE_MRI_GARK_ERK33a", 0);
  o.max_dt = 0.5;
  o.mri_slow_fraction = 0.5;
  StepperStats s;
  const std::vector<Real> y = run(sys, o, y0, 1.0, &s);
  ASSERT_EQ(s.levels.size(), 3u);
  EXPECT_EQ(s.steps, 2);
  EXPECT_EQ(s.levels[1].steps, 2 * 3 * 11);  // 3 fast stages of 0.5/3 each, 32/3 -> 11 middle steps
  for (const auto& call : sys.calls)
    EXPECT_TRUE(call.active == kSlow || call.active == kMiddle || call.active == kFast || call.active == kMiddleAndFast);
  // The slow step's error dominates: as large as a two-level run's (fast step 0.5/1024 for both
  // pairs), within 1 %.
  OscillatorEnsemble two_sys = three_scales();
  o.mri_levels = 2;
  const std::vector<Real> y2 = run(two_sys, o, y0, 1.0);
  const Real error = max_error(y, sys.exact(y0, 1.0)), error2 = max_error(y2, sys.exact(y0, 1.0));
  std::printf("adaptive, max_dt 0.5: error %.4e with 3 levels, %.4e with 2\n", error, error2);
  EXPECT_NEAR(error, error2, 0.01 * error2);
}

// A short span: power-of-two levels 0, 1, 2 (w = 1, 3, 5; T = 0.5) become MRI levels 0, 1, 2 with
// steps T, T/2, T/4: the deepest is mri_ratio = 4 below the slow step, as in a two-level run, not
// 4 below the middle. Each slow step: 3 stages of T/3, one middle step each (T/2 > T/3), whose 3
// stages of T/9 take one fast step each: 6 middle and 18 fast steps in all.
TEST(MriNested, AShortSpanSharesTheRatioAmongTheLevels) {
  OscillatorEnsemble sys({1, 1, 1, 1, 3, 3, 5, 5}, 0.3);
  StepperOptions o = nested("ARKODE_MRI_GARK_ERK33a", 0);
  o.max_dt = 0.5;
  o.mri_slow_fraction = 0.5;
  o.mri_ratio = 4;
  StepperStats s;
  run(sys, o, initial_state(sys, false), 1.0, &s);
  ASSERT_EQ(s.levels.size(), 3u);
  EXPECT_EQ(s.steps, 2);
  EXPECT_EQ(s.levels[1].steps, 6);
  EXPECT_EQ(s.levels[2].steps, 18);
}

// Levels deeper than the deepest occupied one get no integrator: three levels with the third
// empty are the two-level run, bit for bit (adaptive: power-of-two levels 0 and 1 only).
TEST(MriNested, AnEmptyDeepestLevelIsTheTwoLevelRun) {
  auto run_levels = [](int levels, StepperStats* stats) {
    OscillatorEnsemble sys({1, 1, 1, 1, 1, 1, 3, 3}, 0.3);
    StepperOptions o = nested("ARKODE_MRI_GARK_ERK33a", 0, 20, levels);
    o.max_dt = 0.5;
    o.mri_slow_fraction = 0.5;
    return run(sys, o, initial_state(sys, false), 2.0, stats);
  };
  StepperStats s2, s3;
  const std::vector<Real> y2 = run_levels(2, &s2), y3 = run_levels(3, &s3);
  for (std::size_t k = 0; k < y2.size(); ++k) EXPECT_EQ(y3[k], y2[k]) << "entry " << k;
  ASSERT_EQ(s3.levels.size(), 3u);
  EXPECT_EQ(s3.levels[2].steps, 0);
  EXPECT_EQ(s3.levels[1].steps, s2.levels[1].steps);
  EXPECT_EQ(s3.particle_evals, s2.particle_evals);
}

// When the deepest occupied level moves, the integrators are made afresh between slow steps:
// before, the run is the two-level one bit for bit; after, particle 0 alone is evaluated on the
// third level, and the run is, bit for bit, a three-level stepper started afresh at the switch.
TEST(MriNested, ANewDeepestLevelGetsItsIntegrator) {
  // h = 1/16: the slow steps land on t_switch exactly, with or without a stop there.
  const Real t_switch = 0.5, h = 0.0625, before = t_switch - h;  // (two levels cannot bin particle 0 after)
  auto run_from = [&](int levels, Real t0, const std::vector<Real>& y0, Real t_end, StepperStats* stats) {
    SwitchingEnsemble sys(t_switch, 0.001);  // particle 0 onto the third level (h / 400) from t_switch
    sys.record_calls = true;
    auto stepper = make_stepper(sys, nested("ARKODE_MRI_GARK_ERK33a", h, 20, levels), t0, y0.data());
    std::vector<Real> y(y0.size());
    Real t = t0;
    EXPECT_EQ(stepper->advance(t_end, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
    if (stats) *stats = stepper->stats();
    for (const auto& call : sys.calls) {  // a call of particle 0 alone: the third level, after the switch
      if (call.active == std::vector<std::size_t>{0}) {
        EXPECT_GE(call.t, t_switch);
      }
    }
    return y;
  };
  const std::vector<Real> y0 = initial_state(three_scales(), false);
  StepperStats s;
  const std::vector<Real> before2 = run_from(2, 0, y0, before, nullptr), before3 = run_from(3, 0, y0, before, &s);
  for (std::size_t k = 0; k < before2.size(); ++k) EXPECT_EQ(before3[k], before2[k]) << "entry " << k;
  EXPECT_EQ(s.levels[2].steps, 0);
  const std::vector<Real> at_switch = run_from(3, 0, y0, t_switch, nullptr);
  const std::vector<Real> through = run_from(3, 0, y0, 1.0, &s), fresh = run_from(3, t_switch, at_switch, 1.0, nullptr);
  for (std::size_t k = 0; k < fresh.size(); ++k) EXPECT_EQ(through[k], fresh[k]) << "entry " << k;
  EXPECT_GT(s.levels[2].steps, 0);
  EXPECT_GT(s.levels[2].rhs_evals, 0);
  EXPECT_EQ(s.levels[2].particle_evals, s.levels[2].rhs_evals);  // particle 0 only
}

// Where the scales separate, nesting pays: the w = 50 pair on a middle level at h/20 instead of
// the fast level at h/400 (two levels, ratio 400: the same slow and fastest steps). With ERK45a
// the error stays the two-level one (h = 0.2, 0.1, 0.05: 2.281 / 2.281, 8.970e-2 / 8.970e-2,
// 5.52e-3 / 4.34e-3) at 1.90x fewer particle evaluations. (ERK33a, third order on the middle
// level: 5.75 / 2.28, 0.597 / 0.0895, 0.0594 / 0.0043 at the same saving: see "Accuracy per level"
// in docs/time_integration.md.)
TEST(MriNested, ThreeLevelsMatchTwoAtFewerEvaluations) {
  for (const Real h : {0.2, 0.1, 0.05}) {
    OscillatorEnsemble two = three_scales(), three = three_scales();
    const std::vector<Real> y0 = initial_state(two, false);
    StepperStats s2, s3;
    const std::vector<Real> y2 = run(two, nested("ARKODE_MRI_GARK_ERK45a", h, 400, 2), y0, 1.0, &s2);
    const std::vector<Real> y3 = run(three, nested("ARKODE_MRI_GARK_ERK45a", h, 20, 3), y0, 1.0, &s3);
    const std::vector<Real> exact = two.exact(y0, 1.0);
    const Real e2 = max_error(y2, exact), e3 = max_error(y3, exact);
    const Real saving = static_cast<Real>(s2.particle_evals) / static_cast<Real>(s3.particle_evals);
    std::printf("h %.2f: 2 levels error %.3e, %ld evaluations; 3 levels %.3e, %ld (%.2fx fewer)\n", h, e2,
                s2.particle_evals, e3, s3.particle_evals, saving);
    EXPECT_LT(e3, 1.3 * e2) << "h " << h;
    EXPECT_GT(saving, 1.85) << "h " << h;
  }
}

// An exception in the middle level's RHS (two C layers down: MRIStep, the wrapper, the middle
// MRIStep) ends the run as Failed with its message, at the last accepted slow step.
class ThrowingMiddle : public OscillatorEnsemble {
 public:
  ThrowingMiddle() : OscillatorEnsemble({1, 1, 1, 1, 50, 50, 900, 900}, 0.3) {}
  int rhs_subset(Real t, const Real* y, std::span<const std::size_t> active, Real* ydot) override {
    if (t > 0.3 && active.size() == 2 && active[0] == 4) throw std::runtime_error("middle level exploded");
    return OscillatorEnsemble::rhs_subset(t, y, active, ydot);
  }
};

TEST(MriNested, AnExceptionInTheMiddleLevelIsAFailureWithItsMessage) {
  ThrowingMiddle sys;
  const std::vector<Real> y0 = initial_state(sys, false);
  auto stepper = make_stepper(sys, nested("ARKODE_MRI_GARK_ERK33a", 0.1), 0, y0.data());
  std::vector<Real> y(y0.size());
  Real t = 0;
  EXPECT_EQ(stepper->advance(1.0, y.data(), t), AdvanceStatus::Failed);
  EXPECT_NE(stepper->failure_reason().find("middle level exploded"), std::string::npos) << stepper->failure_reason();
  EXPECT_LE(t, 0.3 + 1e-12);  // the last accepted slow step (0.2: the step to 3 x 0.1 > 0.3 ends
  EXPECT_GE(t, 0.2 - 1e-12);  // with a middle evaluation past 0.3)
}

TEST(MriNested, BadLevelOptionsAreOneLineInvalidArguments) {
  OscillatorEnsemble sys = three_scales();
  const std::vector<Real> y0 = initial_state(sys, false);
  auto expect_error = [&](const StepperOptions& o, const std::string& what) { expect_invalid_argument(sys, o, y0, what); };
  expect_error(nested("ARKODE_MIS_KW3", 0.1, 20, 1), "mri_levels=1: must be in 2..8");
  expect_error(nested("ARKODE_MIS_KW3", 0.1, 20, 9), "mri_levels=9: must be in 2..8");
  expect_error(nested("ARKODE_MIS_KW3", 0.1, 1, 3), "mri_ratio=1: must be >= 2 with mri_levels > 2");
  try {  // h / 4^2 = 0.00625 > 1/900: the w = 900 pair has no level
    make_stepper(sys, nested("ARKODE_MIS_KW3", 0.1, 4, 3), 0, y0.data());
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("raise mri_ratio or mri_levels"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sphark::test
