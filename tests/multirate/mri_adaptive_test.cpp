// MRIStep with power-of-two slow steps (fixed_dt = 0, max_dt = T; mri_split.hpp): the slow level
// holds mri_slow_fraction of the particles, the fast step is the deepest level's.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "oscillator_ensemble.hpp"
#include "sphark/integrate/stepper.hpp"
#include "switching_ensemble.hpp"

namespace sphark::test {
namespace {

StepperOptions adaptive(Real max_dt) {
  StepperOptions o;
  o.method = "mri-ARKODE_MRI_GARK_ERK33a";
  o.max_dt = max_dt;
  o.mri_ratio = 1;
  o.mri_slow_fraction = 0.75;  // the 6 slow oscillators of 8
  return o;
}

Real run(OdeSystem& sys, const StepperOptions& o, Real t0, const std::vector<Real>& y0, Real t_end,
         std::vector<Real>& y, StepperStats* stats = nullptr) {
  auto stepper = make_stepper(sys, o, t0, y0.data());
  y.assign(y0.size(), 0);
  Real t = t0;
  EXPECT_EQ(stepper->advance(t_end, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
  if (stats) *stats = stepper->stats();
  return t;
}

// Stable steps 1 and 1/100 on the levels of max_dt = 0.1: slow on level 0 (h = 0.1), fast on
// level 4 (0.1 / 16 <= 0.01): the same run as the fixed slow step 0.1 with ratio 16.
TEST(MriAdaptive, ItsStepsAreThePowerOfTwoLevels) {
  OscillatorEnsemble a = OscillatorEnsemble({1, 1, 1, 1, 1, 1, 100, 100}, 0.3), b = a;
  const std::vector<Real> y0 = excited_state(8);
  std::vector<Real> ya, yb;
  StepperStats s;
  run(a, adaptive(0.1), 0, y0, 1.0, ya, &s);
  StepperOptions fixed = adaptive(0.1);
  fixed.max_dt = 0;
  fixed.fixed_dt = 0.1;
  fixed.mri_ratio = 16;
  run(b, fixed, 0, y0, 1.0, yb);
  EXPECT_EQ(s.steps, 10);
  EXPECT_EQ(s.levels[0].particle_evals, 6 * s.levels[0].rhs_evals);
  EXPECT_EQ(s.levels[1].particle_evals, 2 * s.levels[1].rhs_evals);
  for (std::size_t k = 0; k < ya.size(); ++k) EXPECT_EQ(ya[k], yb[k]) << "entry " << k;
}

// From t = 0.5 every stable step halves: the slow step becomes 0.05, the fast 0.1 / 256; the
// run then goes on as a fresh stepper started there, bit for bit.
TEST(MriAdaptive, TheSlowStepFollowsTheLevels) {
  HalvingEnsemble a(0.5), b(0.5);
  const std::vector<Real> y0 = excited_state(8);
  std::vector<Real> y_half, ya, yb;
  StepperStats s;
  StepperOptions o = adaptive(0.1);
  o.cfl_safety = 0.15;  // slow: 0.15 (level 0), then 0.075 (level 1)
  {
    HalvingEnsemble c(0.5);
    run(c, o, 0, y0, 0.5, y_half);
  }
  run(a, o, 0, y0, 1.0, ya, &s);
  EXPECT_EQ(s.steps, 5 + 10);  // 0.1 until 0.5, then 0.05
  run(b, o, 0.5, y_half, 1.0, yb);
  for (std::size_t k = 0; k < ya.size(); ++k) EXPECT_EQ(ya[k], yb[k]) << "entry " << k;
}

TEST(MriAdaptive, OrderAsMaxDtHalves) {
  std::vector<Real> e;
  for (int k = 0; k < 4; ++k) {
    OscillatorEnsemble sys({1, 1, 1, 1, 1, 1, 100, 100}, 0.3);
    const std::vector<Real> y0 = sys.project_below(excited_state(8), 10);  // the slow manifold
    StepperOptions o = adaptive(0.1 / (1 << k));
    o.cfl_safety = 10 * o.max_dt;  // the levels fixed as max_dt halves: slow 0, fast 4
    o.mri_fast_table = "ARKODE_DORMAND_PRINCE_7_4_5";
    std::vector<Real> y;
    run(sys, o, 0, y0, 1.0, y);
    const std::vector<Real> exact = sys.exact(y0, 1.0);
    Real err = 0;
    for (std::size_t i = 0; i < y.size(); ++i) err = std::max(err, std::abs(y[i] - exact[i]));
    e.push_back(err);
  }
  for (std::size_t k = 1; k < e.size(); ++k) {
    const Real order = std::log2(e[k - 1] / e[k]);
    std::printf("adaptive ERK33a: error %.3e -> %.3e, order %.2f\n", e[k - 1], e[k], order);
    EXPECT_GE(order, 3 - 0.3);
  }
}

TEST(MriAdaptive, NeedsASlowFractionInZeroOne) {
  OscillatorEnsemble sys({1, 100}, 0.3);
  const std::vector<Real> y0 = excited_state(2);
  StepperOptions o = adaptive(0.1);
  o.mri_slow_fraction = 1.5;
  EXPECT_THROW(make_stepper(sys, o, 0, y0.data()), std::invalid_argument);
}

}  // namespace
}  // namespace sphark::test
