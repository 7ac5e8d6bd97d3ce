// Kick-drift-kick leapfrog on the harmonic oscillator.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "test_systems.hpp"

namespace sphark::test {
namespace {

Real leapfrog_error(Real dt, Real T) {
  Oscillator sys;
  const Real y0[2] = {1, 0};
  auto stepper = make_stepper(sys, options("leapfrog", 1e-6, dt), 0, y0);
  Real y[2], t = 0;
  EXPECT_EQ(stepper->advance(T, y, t), AdvanceStatus::Reached);
  EXPECT_EQ(t, T);
  return std::max(std::abs(y[0] - std::cos(T)), std::abs(y[1] + std::sin(T)));
}

TEST(Leapfrog, SecondOrderWithFixedStep) {
  const Real T = 4;
  const Real e1 = leapfrog_error(T / 40, T), e2 = leapfrog_error(T / 80, T), e3 = leapfrog_error(T / 160, T);
  std::printf("leapfrog errors %.3e %.3e %.3e orders %.3f %.3f\n", e1, e2, e3, std::log2(e1 / e2),
              std::log2(e2 / e3));
  EXPECT_NEAR(std::log2(e1 / e2), 2.0, 0.3);
  EXPECT_NEAR(std::log2(e2 / e3), 2.0, 0.3);
}

// Velocity-dependent force and an extra evolved field: the predictor w* keeps second order
// for every component (x, v and the "energy" e, which is kicked like the velocity).
TEST(Leapfrog, SecondOrderWithVelocityDependentForceAndExtraField) {
  DampedWithEnergy sys(0.3);
  const Real T = 4;
  const std::vector<Real> y0 = sys.exact(0), y_end = sys.exact(T);
  Real errors[3][3];
  for (int i = 0; i < 3; ++i) {
    auto stepper = make_stepper(sys, options("leapfrog", 1e-6, T / (40 << i)), 0, y0.data());
    std::vector<Real> y(3);
    Real t = 0;
    ASSERT_EQ(stepper->advance(T, y.data(), t), AdvanceStatus::Reached);
    for (int k = 0; k < 3; ++k) errors[i][k] = std::abs(y[k] - y_end[k]);
  }
  for (int k = 0; k < 3; ++k) {
    std::printf("damped leapfrog component %d: errors %.3e %.3e %.3e orders %.3f %.3f\n", k, errors[0][k],
                errors[1][k], errors[2][k], std::log2(errors[0][k] / errors[1][k]), std::log2(errors[1][k] / errors[2][k]));
    EXPECT_NEAR(std::log2(errors[1][k] / errors[2][k]), 2.0, 0.3) << "component " << k;
  }
}

// For x'' = -x the KDK map conserves the shadow energy v² + (1 - h²/4) x² exactly, so the true
// energy E = (x² + v²)/2 stays within h²/8 of E0 (x0 = 1, v0 = 0) for all time: no drift.
TEST(Leapfrog, EnergyErrorBoundedOverThousandPeriods) {
  Oscillator sys;
  const Real h = 0.1, y0[2] = {1, 0};
  auto stepper = make_stepper(sys, options("leapfrog", 1e-6, h), 0, y0);
  const Real shadow0 = 1 - h * h / 4;
  Real y[2], t = 0, max_energy_error = 0, max_shadow_error = 0;
  const int periods = 1000;
  for (int p = 1; p <= periods; ++p) {
    // Output times on the step grid so that every step has length h.
    const Real t_out = h * std::round(p * 2 * kPi / h);
    ASSERT_EQ(stepper->advance(t_out, y, t), AdvanceStatus::Reached);
    const Real energy = 0.5 * (y[0] * y[0] + y[1] * y[1]);
    max_energy_error = std::max(max_energy_error, std::abs(energy - 0.5));
    max_shadow_error = std::max(max_shadow_error, std::abs(y[1] * y[1] + shadow0 * y[0] * y[0] - shadow0));
  }
  const StepperStats st = stepper->stats();
  std::printf("leapfrog %ld steps: max |E-E0| = %.3e (bound h^2/8 = %.3e), shadow drift %.3e\n", st.steps,
              max_energy_error, h * h / 8, max_shadow_error);
  EXPECT_LE(max_energy_error, h * h / 8 + 1e-12);
  EXPECT_LT(max_shadow_error, 1e-12);  // round-off only (measured 2e-14)
  EXPECT_EQ(st.rhs_evals, st.steps + 1);  // one RHS per step (FSAL) plus the initial one
}

// Without fixed_dt the step follows cfl_safety * max_stable_dt, recomputed every step.
class CflOscillator : public Oscillator {
 public:
  Real max_stable_dt(Real, const Real* y, const Real*) noexcept override { return 0.05 + 0.05 * std::abs(y[0]); }
};

TEST(Leapfrog, StepFollowsMaxStableDt) {
  CflOscillator sys;
  const Real y0[2] = {1, 0};
  StepperOptions o = options("leapfrog");
  o.cfl_safety = 0.5;
  auto stepper = make_stepper(sys, o, 0, y0);
  Real y[2], t = 0;
  ASSERT_EQ(stepper->advance(0.0495, y, t), AdvanceStatus::Reached);  // first step: 0.5 * 0.1
  EXPECT_EQ(stepper->stats().steps, 1);
  EXPECT_DOUBLE_EQ(stepper->stats().last_dt, 0.0495);
  ASSERT_EQ(stepper->advance(10, y, t), AdvanceStatus::Reached);
  const StepperStats st = stepper->stats();
  EXPECT_GT(st.steps, static_cast<long>(10 / 0.05));
  EXPECT_LT(st.steps, static_cast<long>(10 / 0.025) + 2);
  EXPECT_NEAR(y[0], std::cos(10.0), 1e-2);
}

}  // namespace
}  // namespace sphark::test
