// "leapfrog-blocks" interrupted inside a top step (StepperOptions::interrupt: Ctrl-C, a
// checkpoint request): the step returns the last synchronised state, and taking it again gives
// the run that was never interrupted bit for bit — its binning, steps and levels included.
#include <gtest/gtest.h>

#include <cmath>

#include "sphark/integrate/stepper.hpp"
#include "switching_ensemble.hpp"

namespace sphark::test {
namespace {

struct Outcome {
  std::vector<Real> y;
  StepperStats stats;
};

// Outputs at 0.7, 0.735 (a shorter top step that lands there: the ladder changes, and the cycle
// bins afresh: the fast oscillators, stable step 0.01, go from h/8 to 0.035/4, where a run that
// kept their levels with the hysteresis margin would hold them on 0.035/8) and 1.0, top step 0.05;
// interrupted at the third evaluation of the landing cycle when `interrupt_at_landing`, then taken
// again.
Outcome run(bool interrupt_at_landing) {
  const Real h = 0.05;
  HystereticEnsemble sys(0.2, 0.4, 1.1 * h / 4);  // particle 0 held on a level by the hysteresis
  std::vector<Real> y = excited_state(sys.n());
  bool armed = false;
  int polls = 0;
  StepperOptions o;
  o.method = "leapfrog-blocks";
  o.fixed_dt = h;
  o.cfl_safety = 1;
  o.partition_hysteresis = 0.25;
  o.interrupt = [&] { return armed && ++polls == 3; };
  auto stepper = make_stepper(sys, o, 0, y.data());
  Real t = 0;
  EXPECT_EQ(stepper->advance(0.7, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
  if (interrupt_at_landing) {
    const std::vector<Real> before = y;
    armed = true;
    EXPECT_EQ(stepper->advance(0.735, y.data(), t), AdvanceStatus::Interrupted);
    armed = false;
    EXPECT_EQ(t, 0.7);
    EXPECT_EQ(y, before);
  }
  EXPECT_EQ(stepper->advance(0.735, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
  EXPECT_EQ(stepper->advance(1.0, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
  return {y, stepper->stats()};
}

TEST(BlockInterrupt, ACycleTakenAgainAfterAnInterruptIsTheUninterruptedOne) {
  const Outcome whole = run(false), again = run(true);
  ASSERT_EQ(whole.y.size(), again.y.size());
  for (std::size_t k = 0; k < whole.y.size(); ++k) EXPECT_EQ(again.y[k], whole.y[k]) << "entry " << k;
  EXPECT_EQ(again.stats.steps, whole.stats.steps);
  EXPECT_EQ(again.stats.rhs_evals, whole.stats.rhs_evals);
  // the particle evaluations count the work done (the guard's count): the two evaluations of
  // the interrupted cycle before its third poll stay in it, at most two of all 8 particles
  EXPECT_GT(again.stats.particle_evals, whole.stats.particle_evals);
  EXPECT_LE(again.stats.particle_evals, whole.stats.particle_evals + 2 * 8);
  ASSERT_EQ(again.stats.levels.size(), whole.stats.levels.size());
  for (std::size_t l = 0; l < whole.stats.levels.size(); ++l) {
    EXPECT_EQ(again.stats.levels[l].steps, whole.stats.levels[l].steps) << "level " << l;
    EXPECT_EQ(again.stats.levels[l].particle_evals, whole.stats.levels[l].particle_evals) << "level " << l;
  }
  EXPECT_EQ(again.stats.last_dt, whole.stats.last_dt);
  std::printf("%ld events on %zu levels in both runs; particle evaluations %ld uninterrupted, %ld interrupted\n",
              whole.stats.steps, whole.stats.levels.size(), whole.stats.particle_evals, again.stats.particle_evals);
}

}  // namespace
}  // namespace sphark::test
