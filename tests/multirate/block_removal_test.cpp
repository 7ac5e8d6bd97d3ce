// Particles removed inside a top step of block steps (StepperOptions::remove_active: gas accreted
// at the events of its own steps, Phantom's way; issue #17). On uncoupled oscillators (kappa = 0)
// each particle's state depends on its own steps only, so removing a fast one at an event must
// leave every other particle exactly where a run without it from the start takes it, bit for bit,
// at one evaluation of the removed particle per event it lived through; a step that is
// interrupted after a removal rolls back to its start with the system's particles given back.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "oscillator_ensemble.hpp"
#include "sphark/integrate/stepper.hpp"

namespace sphark::test {
namespace {

const std::vector<Real> kOmega = {1, 1, 1, 1, 100, 100, 100, 1};
constexpr std::size_t kGone = 5;  // a fast one
constexpr Real kTop = 0.1;

// y without particle i (positions x_0..x_{n-1}, then velocities) and where each entry came from.
StepperOptions::Removal without(const Real* y, std::size_t n, std::size_t i) {
  StepperOptions::Removal r;
  for (std::size_t k = 0; k < 2 * n; ++k)
    if (k % n != i) r.y.push_back(y[k]), r.entry_source.push_back(k);
  return r;
}

StepperOptions blocks() {
  StepperOptions o;
  o.method = "leapfrog-blocks";
  o.fixed_dt = kTop;
  o.cfl_safety = 1.5 * kTop;  // slow ones on level 0, fast ones on level 7 (kTop / 128)
  return o;
}

struct RemovalRun {
  OscillatorEnsemble sys{kOmega, 0.0};
  int calls = 0, undone = 0;
  std::vector<std::vector<std::size_t>> active_sets;
  StepperOptions options(int remove_at_call) {
    StepperOptions o = blocks();
    o.remove_active = [this, remove_at_call](Real, const Real* y, const std::vector<std::size_t>& active) {
      active_sets.push_back(active);
      if (++calls != remove_at_call) return std::optional<StepperOptions::Removal>{};
      EXPECT_TRUE(std::find(active.begin(), active.end(), kGone) != active.end());
      StepperOptions::Removal r = without(y, sys.n(), kGone);
      sys.remove_particle(kGone);
      return std::optional<StepperOptions::Removal>(std::move(r));
    };
    o.undo_removals = [this] {
      ++undone;
      sys.insert_particle(kGone, kOmega[kGone]);
    };
    return o;
  }
};

TEST(BlockRemoval, TheOthersGoOnBitForBitAsIfTheRemovedParticleHadNeverBeen) {
  RemovalRun run;
  const std::vector<Real> y0 = excited_state(kOmega.size());
  auto stepper = make_stepper(run.sys, run.options(5), 0, y0.data());
  std::vector<Real> y(y0.size());
  Real t = 0;
  ASSERT_EQ(stepper->advance(1.0, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
  ASSERT_EQ(run.sys.n(), kOmega.size() - 1);
  y.resize(run.sys.size());
  // the active sets the system saw: the fast ones at each event inside the first top step
  ASSERT_GE(run.active_sets.size(), 5u);
  EXPECT_EQ(run.active_sets[0], (std::vector<std::size_t>{4, 5, 6}));
  EXPECT_EQ(run.active_sets[5], (std::vector<std::size_t>{4, 5}));  // renumbered after the removal

  std::vector<Real> omega_rest = kOmega;
  omega_rest.erase(omega_rest.begin() + kGone);
  OscillatorEnsemble rest(omega_rest, 0.0);
  const std::vector<Real> y0_rest = without(y0.data(), kOmega.size(), kGone).y;
  auto reference = make_stepper(rest, blocks(), 0, y0_rest.data());
  std::vector<Real> yr(y0_rest.size());
  Real tr = 0;
  ASSERT_EQ(reference->advance(1.0, yr.data(), tr), AdvanceStatus::Reached);
  EXPECT_EQ(t, tr);
  EXPECT_EQ(y, yr);
  // the removed particle's evaluations: the initial one and one at each of the 5 events it saw
  EXPECT_EQ(stepper->stats().particle_evals, reference->stats().particle_evals + 1 + 5);
  EXPECT_EQ(run.undone, 0);
}

TEST(BlockRemoval, AStepInterruptedAfterARemovalRollsBackWithTheParticlesGivenBack) {
  RemovalRun run;
  const std::vector<Real> y0 = excited_state(kOmega.size());
  StepperOptions o = run.options(3);
  int polls = 0;
  o.interrupt = [&polls] { return ++polls == 10; };  // after the removal, inside the first top step
  auto stepper = make_stepper(run.sys, o, 0, y0.data());
  std::vector<Real> y(y0.size());
  Real t = -1;
  ASSERT_EQ(stepper->step(1.0, y.data(), t), AdvanceStatus::Interrupted) << stepper->failure_reason();
  EXPECT_EQ(run.undone, 1);
  EXPECT_EQ(run.sys.n(), kOmega.size());
  EXPECT_EQ(t, 0.0);
  EXPECT_EQ(y, y0);
  // and it goes on from there as a run that never removed anything
  std::vector<Real> ya(y0.size()), yb(y0.size());
  Real ta = 0, tb = 0;
  run.calls = -1000;  // no more removals
  ASSERT_EQ(stepper->advance(0.3, ya.data(), ta), AdvanceStatus::Reached) << stepper->failure_reason();
  OscillatorEnsemble all(kOmega, 0.0);
  auto plain = make_stepper(all, blocks(), 0, y0.data());
  ASSERT_EQ(plain->advance(0.3, yb.data(), tb), AdvanceStatus::Reached);
  EXPECT_EQ(ya, yb);
}

// A particle made at an event (a sink made of removed gas: entries without a source) is
// evaluated there and starts its own steps at that event: on uncoupled oscillators its state at
// the end of the top step is that of KDK steps of its level from the event on.
std::pair<Real, Real> kdk(Real x, Real v, Real w, Real dt, int steps) {
  for (int s = 0; s < steps; ++s) {
    v -= 0.5 * dt * w * w * x;
    x += dt * v;
    v -= 0.5 * dt * w * w * x;
  }
  return {x, v};
}

TEST(BlockRemoval, AParticleMadeAtAnEventStartsItsStepsThere) {
  OscillatorEnsemble sys(kOmega, 0.0);
  const std::size_t n = kOmega.size();
  constexpr Real kNewX = 0.3, kNewV = -2.0;
  int calls = 0;
  StepperOptions o = blocks();
  o.remove_active = [&](Real, const Real* y, const std::vector<std::size_t>&) {
    if (++calls != 5) return std::optional<StepperOptions::Removal>{};
    StepperOptions::Removal r = without(y, n, kGone);  // n - 1 particles, then the new one
    r.y.insert(r.y.begin() + static_cast<std::ptrdiff_t>(n - 1), kNewX);
    r.entry_source.insert(r.entry_source.begin() + static_cast<std::ptrdiff_t>(n - 1), ~std::size_t{0});
    r.y.push_back(kNewV);
    r.entry_source.push_back(~std::size_t{0});
    sys.remove_particle(kGone);
    sys.insert_particle(n - 1, 100);
    return std::optional<StepperOptions::Removal>(std::move(r));
  };
  o.undo_removals = [] {};
  const std::vector<Real> y0 = excited_state(n);
  auto stepper = make_stepper(sys, o, 0, y0.data());
  std::vector<Real> y(y0.size());
  Real t = 0;
  ASSERT_EQ(stepper->step(1.0, y.data(), t), AdvanceStatus::Stepped) << stepper->failure_reason();
  EXPECT_EQ(t, kTop);
  const Real fine = kTop / 128;
  const auto [x, v] = kdk(kNewX, kNewV, 100, fine, 128 - 5);
  EXPECT_NEAR(y[n - 1], x, 1e-13);
  EXPECT_NEAR(y[2 * n - 1], v, 1e-11);
  // the evaluations: the initial 8; 3 fast ones at each of the 128 events (the removed one at the
  // first 5, the new one from the 6th), the new one's own at the 5th; the 5 slow ones at the end
  EXPECT_EQ(stepper->stats().particle_evals, 8 + 3 * 128 + 1 + 5);
}

// StepperOptions::wake_next: a particle named at an event ends its step at the next one (cut
// back as a woken particle is) and is evaluated there; named nowhere, a slow oscillator is
// evaluated only at the end of the top step.
TEST(BlockRemoval, AParticleNamedByWakeNextIsEvaluatedAtTheNextEvent) {
  const auto evaluations_of_0 = [](bool wake) {
    OscillatorEnsemble sys(kOmega, 0.0);
    sys.record_calls = true;
    StepperOptions o = blocks();
    int calls = 0;
    o.wake_next = [&calls, wake](Real, const Real*, const std::vector<std::size_t>&) {
      return wake && ++calls == 1 ? std::vector<std::size_t>{0} : std::vector<std::size_t>{};
    };
    const std::vector<Real> y0 = excited_state(kOmega.size());
    auto stepper = make_stepper(sys, o, 0, y0.data());
    std::vector<Real> y(y0.size());
    Real t = 0;
    EXPECT_EQ(stepper->step(1.0, y.data(), t), AdvanceStatus::Stepped);
    std::vector<Real> times;
    for (const OscillatorEnsemble::Call& c : sys.calls)
      if (std::find(c.active.begin(), c.active.end(), 0) != c.active.end()) times.push_back(c.t);
    return times;
  };
  const Real fine = kTop / 128;
  const std::vector<Real> woken = evaluations_of_0(true), plain = evaluations_of_0(false);
  ASSERT_GE(woken.size(), 2u);
  EXPECT_EQ(woken.front(), 2 * fine);  // named at the first event, evaluated at the second
  EXPECT_EQ(woken.back(), kTop);
  EXPECT_EQ(plain, std::vector<Real>{kTop});
}

}  // namespace
}  // namespace sphark::test
