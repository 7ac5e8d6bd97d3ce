// A short water-drop run through the real ARKODE stepper, against the exact ellipse
// (seed 000 §IV-D): up to the first squeeze (t = 0.012, semi-axes 0.52 x 1.9).
//  - the SPH semi-axes of the default drop (1976 particles) follow the exact solution within
//    the 2% target through the squeeze (measured 1.52%; the semi-axis itself changes
//    by 48%). Refinement is not asserted: at these resolutions the error is not monotone in N
//    (spacing 0.08 gives 0.86%, 0.04 gives 1.52%, both at h = 2 spacing; see docs/water_drop.md);
//  - mass is exact by construction; total momentum stays at zero (symmetric forces, symmetric
//    body force about the centre) to round-off of the time integration;
//  - the cleaned run has a mean |div v| at least 2.9x below the control's (measured 3.0x).
#include <gtest/gtest.h>

#include "sphark/integrate/stepper.hpp"
#include "sphark/scenes/water_drop/water_drop.hpp"

using namespace sphark;

namespace {
struct ShortRun {
  Real semi_axis_error = 0;  // max over 0.001 samples
  Real mean_div_v = 0;       // time average of the particle mean |div v|
  Real momentum = 0;         // |P| at the end over m N A R
};

ShortRun run(Real spacing, bool cleaning, Real t_end) {
  WaterDropConfig cfg;
  cfg.spacing = spacing;
  cfg.cleaning = cleaning;
  WaterDrop drop = make_water_drop(cfg);
  StepperOptions o;
  o.method = "ARKODE_BOGACKI_SHAMPINE_4_2_3";
  o.rtol = 1e-4;
  o.atol = {1e-6};
  auto stepper = make_stepper(drop.model->system(), o, 0.0, drop.y0.data());
  std::vector<Real> y = drop.y0;
  ShortRun r;
  Real t = 0;
  int samples = 0;
  for (int k = 1; k * 1e-3 <= t_end + 1e-12; ++k) {
    EXPECT_EQ(stepper->advance(k * 1e-3, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
    const auto ax = measure_semi_axes(y.data() + drop.model->layout().offset(Field::Position), drop.particles());
    const auto ex = drop.exact.at(t);
    r.semi_axis_error = std::max({r.semi_axis_error, std::abs(ax.x - ex.a) / ex.a, std::abs(ax.y - ex.b) / ex.b});
    const auto d = drop.model->diagnostics(t, y.data());
    r.mean_div_v += d.mean_abs_div_v;
    r.momentum = d.momentum.norm() / (drop.model->layout().particles() * cfg.rho0 * spacing * spacing * cfg.amplitude);
    ++samples;
  }
  r.mean_div_v /= samples;
  return r;
}
}  // namespace

TEST(ShortWaterDrop, FollowsExactEllipseThroughTheSqueeze) {
  const ShortRun r = run(0.04, true, 0.013);
  std::printf("max semi-axis error to t = 0.013: %.4f\n", r.semi_axis_error);
  EXPECT_LT(r.semi_axis_error, 0.02);
  EXPECT_LT(r.momentum, 1e-9);
}

TEST(ShortWaterDrop, CleaningLowersVelocityDivergence) {
  const ShortRun cleaned = run(0.08, true, 0.006);
  const ShortRun control = run(0.08, false, 0.006);
  std::printf("mean |div v|: cleaned %.4g, control %.4g\n", cleaned.mean_div_v, control.mean_div_v);
  // measured: control / cleaned = 3.014 / 1.004 = 3.00 (484 particles, delta-SPH in both runs)
  EXPECT_GT(control.mean_div_v, 2.9 * cleaned.mean_div_v);
}
