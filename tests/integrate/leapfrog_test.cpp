// Kick-drift-kick leapfrog on the harmonic oscillator, and its corrector iterations (Phantom's
// tolv) on a gyrating particle.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>

#include "../support/gyration_ensemble.hpp"
#include "sphark/integrate/forwarding_system.hpp"
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

// A particle gyrating in a field, a = omega (v_y, -v_x) (the Lorentz force): |v| stays |v0|.
// The force depends on v only. The KDK step evaluates it at the predicted v* = v_n + dt g_n and
// kicks the next step with that value (FSAL): with G = dt g, z = -i omega dt and v complex, the
// step maps (v, G) by M = [[1 + z/2, (1 + z)/2], [z, z]], whose spectral radius exceeds 1
// (1.0267 for omega dt = 0.5): |v| grows by it every step. Iterated until v agrees with its
// prediction (StepperOptions::velocity_tolerance) the step is the trapezoidal rule: |v| is kept.
// Counts the RHS evaluations of the system it forwards to.
class CountingSystem : public ForwardingSystem {
 public:
  CountingSystem(OdeSystem& inner, long& count) : ForwardingSystem(inner), count_(count) {}
  int rhs(Real t, const Real* y, Real* ydot) override {
    ++count_;
    return ForwardingSystem::rhs(t, y, ydot);
  }

 private:
  long& count_;
};

struct GyrationRun {
  Real speed_half = 0, speed_end = 0;  // |v| after steps/2 and after steps
  long iterations = 0;
};

GyrationRun gyrate(Real theta, Real tolerance, int steps) {
  GyrationEnsemble sys({1.0});
  const Real y0[4] = {0, 0, 1, 0};
  StepperOptions o = options("leapfrog", 1e-6, theta);
  o.velocity_tolerance = tolerance;
  auto stepper = make_stepper(sys, o, 0, y0);
  Real y[4], t = 0;
  GyrationRun r;
  EXPECT_EQ(stepper->advance(steps / 2 * theta, y, t), AdvanceStatus::Reached);
  r.speed_half = std::hypot(y[2], y[3]);
  EXPECT_EQ(stepper->advance(steps * theta, y, t), AdvanceStatus::Reached);
  r.speed_end = std::hypot(y[2], y[3]);
  r.iterations = stepper->stats().corrector_iterations;
  return r;
}

TEST(Leapfrog, CorrectorIterationsKeepTheSpeedOfAGyration) {
  const int steps = 400;
  const Real theta = 0.5;
  const std::complex<Real> z(0, -theta), trace = 1.0 + 1.5 * z, root = std::sqrt(trace * trace - 2.0 * z);
  const Real radius = std::max(std::abs(0.5 * (trace + root)), std::abs(0.5 * (trace - root)));
  const GyrationRun off = gyrate(theta, 0, steps), on = gyrate(theta, 1e-12, steps);
  const Real growth = std::pow(off.speed_end / off.speed_half, 2.0 / steps);
  std::printf("gyration, omega dt = %.1f: without iterations |v| %.6g after %d steps, growth per step %.12f "
              "(spectral radius %.12f); with them |v| %.15f (%ld corrector iterations)\n",
              theta, off.speed_end, steps, growth, radius, on.speed_end, on.iterations);
  EXPECT_NEAR(growth, radius, 1e-9);
  EXPECT_EQ(off.iterations, 0);
  EXPECT_NEAR(on.speed_end, 1.0, 1e-9);  // each step converged to 1e-12 x |v|: 400 steps, 4e-10 at most
  EXPECT_GT(on.iterations, steps);       // more than one iteration per step
}

// The iteration v <- v_half + dt/2 a(v) contracts by omega dt / 2 per iteration: at omega dt = 3
// it diverges, at 1.5 it contracts by 0.75, too slowly to reach 1e-12 in 30 iterations, at 0.75
// it converges. So the steps are retried at half the length until they converge (measured: 41
// steps of 0.75 and 79 retries to t = 30), and |v| is kept.
TEST(Leapfrog, AStepWhoseCorrectorDivergesIsRetriedShorter) {
  GyrationEnsemble sys({1.0});
  const Real y0[4] = {0, 0, 1, 0};
  StepperOptions o = options("leapfrog", 1e-6, 3.0);
  o.velocity_tolerance = 1e-12;
  auto stepper = make_stepper(sys, o, 0, y0);
  Real y[4], t = 0;
  ASSERT_EQ(stepper->advance(30, y, t), AdvanceStatus::Reached) << stepper->failure_reason();
  const StepperStats st = stepper->stats();
  std::printf("gyration at omega dt = 3: %ld steps, %ld retries, %ld corrector iterations, |v| %.15f\n", st.steps,
              st.rhs_recoveries, st.corrector_iterations, std::hypot(y[2], y[3]));
  EXPECT_GE(st.rhs_recoveries, st.steps);  // every step was retried at least once
  EXPECT_NEAR(std::hypot(y[2], y[3]), 1.0, 1e-9);
}

// A stop request is heard inside a step's corrector iterations (each one asks), not only between
// steps: a step whose corrector cannot converge (tolerance 1e-300 at omega dt = 3: it diverges,
// and each retry at half the length takes 30 more evaluations) stops after the evaluation that
// saw the request, the state as before the step.
TEST(Leapfrog, AStopRequestEndsTheCorrectorIterationsAtOnce) {
  GyrationEnsemble sys({1.0});
  const Real y0[4] = {0, 0, 1, 0};
  StepperOptions o = options("leapfrog", 1e-6, 3.0);
  o.velocity_tolerance = 1e-300;
  long evaluations = 0;
  CountingSystem counted(sys, evaluations);
  o.interrupt = [&] { return evaluations >= 6; };  // the initial RHS, the step's, four iterations
  auto stepper = make_stepper(counted, o, 0, y0);
  Real y[4], t = -1;
  EXPECT_EQ(stepper->advance(30, y, t), AdvanceStatus::Interrupted);
  EXPECT_EQ(evaluations, 6);
  EXPECT_EQ(t, 0.0);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(y[k], y0[k]) << k;
}

}  // namespace
}  // namespace sphark::test
