// "leapfrog-blocks": Phantom-style power-of-two block steps on the KDK leapfrog (issue #17).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>
#include <stdexcept>

#include "../support/gyration_ensemble.hpp"
#include "oscillator_ensemble.hpp"
#include "pair_springs.hpp"
#include "switching_ensemble.hpp"
#include "sphark/integrate/stepper.hpp"

namespace sphark::test {
namespace {

OscillatorEnsemble ensemble() { return OscillatorEnsemble({1, 1, 1, 1, 1, 1, 100, 100}, 0.3); }

std::vector<Real> initial_state(const OscillatorEnsemble& sys) {
  return sys.project_below(excited_state(sys.n()), 10);  // the slow manifold (see mri_order_test.cpp)
}

// Top step h; cfl_safety = 1.5 h puts the slow oscillators (stable step 1) on level 0 and the
// fast ones (1/100) on level 7 (h / 128) for every h, so that all steps halve with h.
StepperOptions blocks(Real h) {
  StepperOptions o;
  o.method = "leapfrog-blocks";
  o.fixed_dt = h;
  o.cfl_safety = 1.5 * h;
  return o;
}

TEST(BlockSteps, SecondOrderOnTheOscillatorEnsemble) {
  std::vector<Real> e;
  for (int k = 0; k < 4; ++k) {
    const Real h = 0.1 / (1 << k);
    OscillatorEnsemble sys = ensemble();
    const std::vector<Real> y0 = initial_state(sys);
    auto stepper = make_stepper(sys, blocks(h), 0, y0.data());
    std::vector<Real> y(y0.size());
    Real t = 0;
    ASSERT_EQ(stepper->advance(1.0, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
    ASSERT_EQ(t, 1.0);
    e.push_back(max_error(y, sys.exact(y0, 1.0)));
    const StepperStats s = stepper->stats();
    const long cycles = std::lround(1.0 / h);
    ASSERT_EQ(s.levels.size(), 8u);
    for (int l = 1; l < 7; ++l) EXPECT_EQ(s.levels[l].particle_evals, 0) << "level " << l;
    EXPECT_EQ(s.levels[0].rhs_evals, cycles);        // once per top step
    EXPECT_EQ(s.levels[7].rhs_evals, 128 * cycles);  // every h / 128
    EXPECT_EQ(s.levels[0].particle_evals, 6 * cycles);
    EXPECT_EQ(s.levels[7].particle_evals, 2 * 128 * cycles);
    EXPECT_EQ(s.rhs_evals, 1 + 128 * cycles);  // the initial full RHS, one call per event
    EXPECT_EQ(s.particle_evals, 8 + s.levels[0].particle_evals + s.levels[7].particle_evals);
    std::printf("h=%g: error %.3e, particle evals %ld (global leapfrog at h/128: %ld)\n", h, e.back(),
                s.particle_evals, 8 * (1 + 128 * cycles));
  }
  for (std::size_t k = 1; k < e.size(); ++k) {
    const Real order = std::log2(e[k - 1] / e[k]);
    std::printf("order %.3f\n", order);
    EXPECT_GE(order, 2 - 0.3) << "halving " << k;
  }
}

// StepperOptions::fit_block_cycles: the oscillators' stable steps are 0.34 and 0.0034 x the
// top step h (slow and fast), on which the fixed ladder h/2^l wastes nearly half of each: 4
// slow steps per top step (h/4) and 512 fast ones (h/512). The fitted cycles cut the way to each
// output (every h) into m <= 16 equal cycles of the least work (here the particle evaluations:
// 8 particles make an event cheap): m = 5 (slow steps h/5, fast h/320), 670 evaluations instead
// of 1048 per h. Every output is reached exactly, every
// top step is at most h, the error falls at second order as h halves, and is the fixed cycles'
// times (0.2 / 0.25)^2 = 0.64: the slow oscillators' error dominates, and their steps are h/5
// against h/4.
TEST(BlockSteps, FittedCyclesShiftTheLadderToTheStepsAtSecondOrder) {
  std::vector<Real> e_fixed, e_fitted;
  for (int k = 0; k < 4; ++k) {
    const Real h = 0.1 / (1 << k);
    long evals[2] = {0, 0};
    for (const bool fit : {false, true}) {
      OscillatorEnsemble sys = ensemble();
      const std::vector<Real> y0 = initial_state(sys);
      StepperOptions o;
      o.method = "leapfrog-blocks";
      o.max_dt = h;
      o.cfl_safety = 0.34 * h;
      o.fit_block_cycles = fit;
      auto stepper = make_stepper(sys, o, 0, y0.data());
      std::vector<Real> y(y0.size());
      Real t = 0;
      const long outputs = std::lround(1.0 / h);
      for (long j = 1; j <= outputs; ++j) {
        const Real t_out = std::min(1.0, static_cast<Real>(j) * h);
        ASSERT_EQ(stepper->advance(t_out, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
        ASSERT_EQ(t, t_out);
        ASSERT_LE(stepper->stats().last_dt, h * (1 + 1e-12));
      }
      (fit ? e_fitted : e_fixed).push_back(max_error(y, sys.exact(y0, 1.0)));
      evals[fit] = stepper->stats().particle_evals;
    }
    std::printf("h=%g: particle evals fixed %ld, fitted %ld (%.3f); error %.3e / %.3e\n", h, evals[0], evals[1],
                static_cast<double>(evals[1]) / static_cast<double>(evals[0]), e_fixed.back(), e_fitted.back());
    EXPECT_EQ(evals[0], 8 + 1048 * std::lround(1.0 / h));
    EXPECT_EQ(evals[1], 8 + 670 * std::lround(1.0 / h));
    EXPECT_NEAR(e_fitted.back() / e_fixed.back(), 0.64, 0.01);  // the slow steps' (0.2 / 0.25)^2
  }
  for (std::size_t k = 1; k < e_fitted.size(); ++k) {
    const Real order = std::log2(e_fitted[k - 1] / e_fitted[k]);
    std::printf("fitted: order %.3f\n", order);
    EXPECT_GE(order, 2 - 0.3) << "halving " << k;
  }
}

// Momentum drift |P(10) - P(0)| with top step h and levels from cfl_safety.
Real momentum_drift(Real h, Real cfl, std::size_t* levels) {
  PairSprings sys;
  const std::vector<Real> y0 = spring_state();
  StepperOptions o;
  o.method = "leapfrog-blocks";
  o.fixed_dt = h;
  o.cfl_safety = cfl;
  auto stepper = make_stepper(sys, o, 0, y0.data());
  std::vector<Real> y(y0.size());
  Real t = 0;
  EXPECT_EQ(stepper->advance(10.0, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
  *levels = stepper->stats().levels.size();
  return std::abs(PairSprings::momentum(y) - PairSprings::momentum(y0));
}

TEST(BlockSteps, MomentumToRoundOffOnOneLevel) {
  std::size_t levels = 0;
  // Stable steps 1/sqrt(25) (soft) and 1/sqrt(160) (stiff): all above h = 0.005.
  const Real drift = momentum_drift(0.005, 1.0, &levels);
  std::printf("one level: momentum drift %.3e\n", drift);
  EXPECT_EQ(levels, 1u);
  EXPECT_LE(drift, 1e-14);
}

// Across levels a pair force is sampled at different times for its two particles: momentum is
// conserved to the time-stepping error only (block_leapfrog_stepper.cpp); measured here.
TEST(BlockSteps, MomentumAcrossLevelsFallsWithTheStep) {
  std::vector<Real> d;
  for (int k = 0; k < 4; ++k) {
    const Real h = 0.05 / (1 << k);
    std::size_t levels = 0;
    d.push_back(momentum_drift(h, 0.3 * h / 0.05, &levels));
    std::printf("h=%g: %zu levels, momentum drift %.3e\n", h, levels, d.back());
    EXPECT_GT(levels, 1u);
  }
  for (std::size_t k = 1; k < d.size(); ++k) {
    const Real order = std::log2(d[k - 1] / d[k]);
    std::printf("momentum drift order %.3f\n", order);
    EXPECT_GE(order, 2 - 0.3) << "halving " << k;
  }
}

TEST(BlockSteps, OneLevelIsTheGlobalLeapfrog) {
  PairSprings a_sys, b_sys;
  const std::vector<Real> y0 = spring_state();
  StepperOptions o;
  o.method = "leapfrog-blocks";
  o.fixed_dt = 0.005;
  auto a = make_stepper(a_sys, o, 0, y0.data());
  o.method = "leapfrog";
  auto b = make_stepper(b_sys, o, 0, y0.data());
  std::vector<Real> ya(16), yb(16);
  Real ta = 0, tb = 0;
  ASSERT_EQ(a->advance(2.0, ya.data(), ta), AdvanceStatus::Reached);
  ASSERT_EQ(b->advance(2.0, yb.data(), tb), AdvanceStatus::Reached);
  std::printf("one level vs leapfrog: max difference %.3e\n", max_error(ya, yb));
  EXPECT_LE(max_error(ya, yb), 1e-13);
  EXPECT_EQ(a->stats().particle_evals, b->stats().particle_evals);
}

// A restart at (t1, y(t1)) with resume_data (the FSAL derivative and the levels) continues bit
// for bit; particle 0 is held on a deep level by the hysteresis, which binning afresh loses.
TEST(BlockSteps, ARestartCarriesTheLevelsAndTheDerivative) {
  const Real h = 0.05, t1 = 0.7, t2 = 1.0;
  // Advances to each of t_outs in turn (a time loop with an output at t1).
  auto run = [&](Real t0, const std::vector<Real>& y0, const std::vector<Real>& resume, std::vector<Real> t_outs,
                 std::vector<Real>* resume_out) {
    HystereticEnsemble sys(0.2, 0.4, 1.1 * h / 4);  // after 0.4: 1.1 x the level-2 step
    StepperOptions o = blocks(h);
    o.cfl_safety = 1;
    o.resume_data = resume;
    auto stepper = make_stepper(sys, o, t0, y0.data());
    std::vector<Real> y(y0.size());
    Real t = t0;
    for (Real t_end : t_outs)
      EXPECT_EQ(stepper->advance(t_end, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
    if (resume_out) *resume_out = stepper->resume_data();
    return y;
  };
  OscillatorEnsemble sys = ensemble();
  const std::vector<Real> y0 = initial_state(sys);
  std::vector<Real> resume;
  const std::vector<Real> y1 = run(0, y0, {}, {t1}, &resume);
  ASSERT_EQ(resume.size(), 16u + 8u + 1u);
  EXPECT_EQ(resume[16], 3);  // particle 0: held on level 3 (h/8 = 0.00625 <= 0.01), not level 2
  const std::vector<Real> y_continued = run(0, y0, {}, {t1, t2}, nullptr);
  const std::vector<Real> y_restarted = run(t1, y1, resume, {t2}, nullptr);
  const std::vector<Real> y_fresh = run(t1, y1, {}, {t2}, nullptr);
  for (std::size_t k = 0; k < y0.size(); ++k) EXPECT_EQ(y_restarted[k], y_continued[k]) << "entry " << k;
  EXPECT_NE(y_fresh, y_continued);
}

// With fitted cycles every cycle bins afresh from the state and the way to the next output: a
// restart at an output continues bit for bit (on the oscillators of the test above, where the
// fitted cycles are not the fixed ones).
TEST(BlockSteps, ARestartWithFittedCyclesContinuesBitForBit) {
  const Real h = 0.05;
  auto run = [&](Real t0, const std::vector<Real>& y0, const std::vector<Real>& resume, int first, int last,
                 std::vector<Real>* resume_out) {
    OscillatorEnsemble sys = ensemble();
    StepperOptions o;
    o.method = "leapfrog-blocks";
    o.max_dt = h;
    o.cfl_safety = 0.34 * h;
    o.fit_block_cycles = true;
    o.resume_data = resume;
    auto stepper = make_stepper(sys, o, t0, y0.data());
    std::vector<Real> y(y0.size());
    Real t = t0;
    for (int j = first; j <= last; ++j)
      EXPECT_EQ(stepper->advance(j * h, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
    if (resume_out) *resume_out = stepper->resume_data();
    return y;
  };
  OscillatorEnsemble sys = ensemble();
  const std::vector<Real> y0 = initial_state(sys);
  std::vector<Real> resume;
  const std::vector<Real> y1 = run(0, y0, {}, 1, 7, &resume);
  const std::vector<Real> y_continued = run(0, y0, {}, 1, 20, nullptr);
  const std::vector<Real> y_restarted = run(7 * h, y1, resume, 8, 20, nullptr);
  for (std::size_t k = 0; k < y0.size(); ++k) EXPECT_EQ(y_restarted[k], y_continued[k]) << "entry " << k;
}

// resize() between cycles (the time loop's particle changes), here to the same state with the
// carried derivative: the run goes on as a fresh stepper with that derivative whose first cycle
// bins afresh (resume_data: derivative, levels, "bin afresh").
TEST(BlockSteps, ResizeCarriesTheDerivativeAndBinsAfresh) {
  const Real h = 0.05, t1 = 0.5, t2 = 1.0;
  HystereticEnsemble a_sys(0.2, 0.4, 1.1 * h / 4), b_sys(0.2, 0.4, 1.1 * h / 4);
  OscillatorEnsemble shape = ensemble();
  const std::vector<Real> y0 = initial_state(shape);
  StepperOptions o = blocks(h);
  o.cfl_safety = 1;
  auto a = make_stepper(a_sys, o, 0, y0.data());
  std::vector<Real> y1(y0.size()), ya(y0.size()), yb(y0.size());
  Real t = 0;
  ASSERT_EQ(a->advance(t1, y1.data(), t), AdvanceStatus::Reached);
  const std::vector<Real> carried = a->carried_data();
  ASSERT_EQ(carried.size(), y0.size());
  a->resize({y1.data(), nullptr, carried.data()});
  ASSERT_EQ(a->advance(t2, ya.data(), t), AdvanceStatus::Reached) << a->failure_reason();
  o.resume_data = carried;
  o.resume_data.insert(o.resume_data.end(), 8, 0.0);  // levels (binned afresh anyway)
  o.resume_data.push_back(1);                         // bin afresh
  auto b = make_stepper(b_sys, o, t1, y1.data());
  ASSERT_EQ(b->advance(t2, yb.data(), t), AdvanceStatus::Reached) << b->failure_reason();
  for (std::size_t k = 0; k < ya.size(); ++k) EXPECT_EQ(ya[k], yb[k]) << "entry " << k;
}

// Runs `sys` (recording its calls) with block steps of top step h from t = 0 to 1 into y, and
// returns the first time after t_after at which particle 0 (level 0) was evaluated (2 if never).
Real first_evaluation_of_zero(OscillatorEnsemble& sys, Real h, Real t_after, std::vector<Real>& y) {
  sys.record_calls = true;
  const std::vector<Real> y0 = initial_state(sys);
  auto stepper = make_stepper(sys, blocks(h), 0, y0.data());  // levels: slow 0, fast 7
  y.assign(y0.size(), 0);
  Real t = 0;
  EXPECT_EQ(stepper->advance(1.0, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
  Real first = 2;
  for (const auto& call : sys.calls)
    if (call.t > t_after && !call.active.empty() && call.active.front() == 0) first = std::min(first, call.t);
  return first;
}

// Wake-up: particle 0 reports a fast stable step from t = 0.52 on, in the middle of its level-0
// step [0.5, 0.6): it is evaluated within two events after 0.52 (the fast particles' grid,
// h / 128; the stable steps a wake-up reads are those of the event before), not at 0.6, and the
// run keeps second order.
TEST(BlockSteps, AParticleWhoseStableStepFallsIsWokenUp) {
  std::vector<Real> e;
  for (int k = 0; k < 4; ++k) {
    const Real h = 0.1 / (1 << k);
    SwitchingEnsemble sys(0.52);
    std::vector<Real> y;
    const Real first = first_evaluation_of_zero(sys, h, 0.52, y);
    EXPECT_LE(first, 0.52 + 2 * h / 128 + 1e-12) << "h=" << h;
    EXPECT_LT(first, 0.6) << "h=" << h;
    e.push_back(max_error(y, sys.exact(initial_state(sys), 1.0)));
  }
  for (std::size_t k = 1; k < e.size(); ++k) {
    const Real order = std::log2(e[k - 1] / e[k]);
    std::printf("with a wake-up: error %.3e -> %.3e, order %.3f\n", e[k - 1], e[k], order);
    EXPECT_GE(order, 2 - 0.3) << "halving " << k;
  }
}

// Wake-up by a bound that the active particles put on another (OdeSystem::active_stable_dt),
// given at the one event in [0.52, 0.521) only: particle 0 (level 0, its step [0.5, 0.6)) is
// woken at the next event, not at 0.6; with no bound it is not woken.
TEST(BlockSteps, ABoundFromTheActiveParticlesWakesAParticleAtTheNextEvent) {
  const Real h = 0.1;
  for (const Real t_on : {0.52, 2.0}) {
    BoundingEnsemble sys(t_on, t_on + 1e-3);  // one event of the fast grid h / 128 in it
    std::vector<Real> y;
    const Real first = first_evaluation_of_zero(sys, h, 0.52, y);
    if (t_on < 1)
      EXPECT_LE(first, 0.52 + 2 * h / 128 + 1e-12);  // the event after the bound
    else
      EXPECT_GE(first, 0.6 - 1e-9);  // at the end of its step
  }
}

TEST(BlockSteps, BadOptionsAreOneLineInvalidArguments) {
  OscillatorEnsemble sys = ensemble();
  const std::vector<Real> y0 = initial_state(sys);
  StepperOptions o;
  o.method = "leapfrog-blocks";
  try {
    make_stepper(sys, o, 0, y0.data());
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("set fixed_dt or max_dt"), std::string::npos) << e.what();
  }
}

// The block stepper's corrector iterations (StepperOptions::velocity_tolerance, as "leapfrog"):
// without them each particle's |v| grows by the KDK map's spectral radius per own step
// (1.026719404499 at omega dt = 0.5, the leapfrog test's number) — on levels 0 and 2 here;
// with them every |v| stays 1 to 1e-9.
TEST(BlockSteps, CorrectorIterationsKeepEachParticlesSpeed) {
  const Real radius = 1.026719404499;
  for (const Real tolerance : {0.0, 1e-12}) {
    GyrationEnsemble sys({1.0, 4.0});
    std::vector<Real> y = {0, 0, 0, 0, 1, 0, 0, 1};
    StepperOptions o;
    o.method = "leapfrog-blocks";
    o.fixed_dt = 0.5;
    o.velocity_tolerance = tolerance;
    auto stepper = make_stepper(sys, o, 0, y.data());
    Real t = 0;
    ASSERT_EQ(stepper->advance(25, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
    const Real slow_half = std::hypot(y[4], y[5]), fast_half = std::hypot(y[6], y[7]);
    ASSERT_EQ(stepper->advance(50, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
    const StepperStats st = stepper->stats();
    ASSERT_EQ(st.levels.size(), 3u);  // the fast particle on level 2 (0.125)
    const Real slow = std::hypot(y[4], y[5]), fast = std::hypot(y[6], y[7]);
    if (tolerance == 0) {  // the growth of the second half (the dominant mode alone)
      EXPECT_NEAR(std::pow(slow / slow_half, 1.0 / 50), radius, 1e-9);   // 50 steps of 0.5
      EXPECT_NEAR(std::pow(fast / fast_half, 1.0 / 200), radius, 1e-9);  // 200 steps of 0.125
      EXPECT_EQ(st.corrector_iterations, 0);
    } else {
      EXPECT_NEAR(slow, 1.0, 1e-9);
      EXPECT_NEAR(fast, 1.0, 1e-9);
      EXPECT_GT(st.corrector_iterations, 400);  // more than one per evaluation of the fast one
    }
  }
}

}  // namespace
}  // namespace sphark::test
