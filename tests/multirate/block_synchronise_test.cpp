// Block steps synchronised early (StepperOptions::synchronise; issue #17): when the poll says
// so, the top step ends at the next event with every particle's step cut back to it, so that
// sink events happen there and not only once per top step (docs/time_integration.md).
// On uncoupled oscillators (kappa = 0) each particle's state depends on its own steps only, so
// the synchronised state is known exactly: the fast ones (level 7) have taken two KDK steps of
// h/128, the slow ones (level 0), cut back, one KDK step of 2h/128.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "oscillator_ensemble.hpp"
#include "sphark/integrate/stepper.hpp"

namespace sphark::test {
namespace {

const std::vector<Real> kOmega = {1, 1, 1, 1, 1, 1, 100, 100};
constexpr Real kTop = 0.1;

std::vector<Real> initial_state(std::size_t n) {
  std::vector<Real> y(2 * n);
  for (std::size_t i = 0; i < n; ++i) y[i] = std::cos(1.0 + i), y[n + i] = std::sin(2.0 * i);
  return y;
}

// `steps` kick-drift-kick steps of dt of x'' = -w^2 x.
std::pair<Real, Real> kdk(Real x, Real v, Real w, Real dt, int steps) {
  for (int s = 0; s < steps; ++s) {
    v -= 0.5 * dt * w * w * x;
    x += dt * v;
    v -= 0.5 * dt * w * w * x;
  }
  return {x, v};
}

// The slow oscillators (stable step 1) on level 0, the fast ones (1/100) on level 7 (kTop/128).
StepperOptions blocks(std::vector<Real>* polled, int synchronise_at_poll) {
  StepperOptions o;
  o.method = "leapfrog-blocks";
  o.fixed_dt = kTop;
  o.cfl_safety = 1.5 * kTop;
  o.synchronise = [polled, synchronise_at_poll](Real t, const Real*) {
    polled->push_back(t);
    return static_cast<int>(polled->size()) == synchronise_at_poll;
  };
  return o;
}

TEST(BlockSynchronise, EndsTheTopStepAtTheNextEventWithEveryParticleSynchronised) {
  OscillatorEnsemble sys(kOmega, 0.0);
  const std::vector<Real> y0 = initial_state(sys.n());
  std::vector<Real> polled;
  auto stepper = make_stepper(sys, blocks(&polled, 2), 0, y0.data());  // poll 1: the cycle's start
  std::vector<Real> y(y0.size());
  Real t = 0;
  ASSERT_EQ(stepper->step(1.0, y.data(), t), AdvanceStatus::Stepped) << stepper->failure_reason();
  const Real fine = kTop / 128;
  ASSERT_EQ(polled.size(), 2u);
  EXPECT_EQ(polled[0], 0.0);
  EXPECT_EQ(polled[1], fine);
  EXPECT_EQ(t, 2 * fine);  // the event after the poll that asked
  const std::size_t n = sys.n();
  for (std::size_t i = 0; i < n; ++i) {
    const bool fast = kOmega[i] > 1;
    const auto [x, v] = kdk(y0[i], y0[n + i], kOmega[i], fast ? fine : 2 * fine, fast ? 2 : 1);
    EXPECT_NEAR(y[i], x, 1e-15 * (1 + std::abs(x))) << i;
    EXPECT_NEAR(y[n + i], v, 1e-15 * (1 + std::abs(v)) * kOmega[i]) << i;
  }
  const StepperStats st = stepper->stats();
  EXPECT_EQ(st.steps, 2);  // two events
  EXPECT_EQ(st.particle_evals, 8 + 2 + 8);  // the initial RHS, the fast pair, then everyone
}

TEST(BlockSynchronise, TheRunGoesOnFromTheSynchronisedStateAsARestartWouldAndStaysAccurate) {
  OscillatorEnsemble sys(kOmega, 0.3);
  const std::vector<Real> y0 = sys.project_below(initial_state(sys.n()), 10);  // the slow manifold (block_steps_test)
  std::vector<Real> polled;
  auto stepper = make_stepper(sys, blocks(&polled, 40), 0, y0.data());  // somewhere in the first top step
  std::vector<Real> y(y0.size()), ys(y0.size());
  Real t = 0, ts = 0;
  ASSERT_EQ(stepper->step(1.0, ys.data(), ts), AdvanceStatus::Stepped);
  ASSERT_LT(ts, kTop);
  // a restart at the synchronised state with the stepper's resume data takes the same steps
  std::vector<Real> polled_restart;
  StepperOptions o = blocks(&polled_restart, 0);
  o.resume_data = stepper->resume_data();
  auto restarted = make_stepper(sys, o, ts, ys.data());
  ASSERT_EQ(stepper->advance(1.0, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
  std::vector<Real> yr(y0.size());
  Real tr = ts;
  ASSERT_EQ(restarted->advance(1.0, yr.data(), tr), AdvanceStatus::Reached) << restarted->failure_reason();
  EXPECT_EQ(t, 1.0);
  EXPECT_EQ(tr, 1.0);
  EXPECT_EQ(y, yr);
  // against the same run without the early end: within the method's error
  std::vector<Real> unused;
  auto plain = make_stepper(sys, blocks(&unused, -1), 0, y0.data());
  std::vector<Real> yp(y0.size());
  Real tp = 0;
  ASSERT_EQ(plain->advance(1.0, yp.data(), tp), AdvanceStatus::Reached);
  const std::vector<Real> exact = sys.exact(y0, 1.0);
  Real e_sync = 0, e_plain = 0;
  for (std::size_t k = 0; k < y.size(); ++k)
    e_sync = std::max(e_sync, std::abs(y[k] - exact[k])), e_plain = std::max(e_plain, std::abs(yp[k] - exact[k]));
  std::printf("error at t = 1: synchronised once %.3e, never %.3e\n", e_sync, e_plain);
  EXPECT_GT(e_sync, 0);
  EXPECT_LT(e_sync, 1.01 * e_plain);  // measured 1.0029: one synchronisation barely changes the error
}

}  // namespace
}  // namespace sphark::test
