// MRIStep bookkeeping (issue #17): the fast and slow sets evaluated are what the partition
// says, the particle evaluations of every stepper, a repartition keeps the state bit for bit,
// the option errors.
#include <gtest/gtest.h>

#include <arkode/arkode_butcher_erk.h>
#include <arkode/arkode_mristep.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "oscillator_ensemble.hpp"
#include "resize_check.hpp"
#include "switching_ensemble.hpp"
#include "sphark/integrate/stepper.hpp"

namespace sphark::test {
namespace {

OscillatorEnsemble ensemble() { return OscillatorEnsemble({1, 1, 1, 1, 1, 1, 100, 100}, 0.3); }

StepperOptions mri(Real h = 0.05, int ratio = 20, const std::string& table = "ARKODE_MRI_GARK_ERK33a") {
  StepperOptions o;
  o.method = "mri-" + table;
  o.fixed_dt = h;
  o.mri_ratio = ratio;
  return o;
}

const std::vector<std::size_t> kSlowSet{0, 1, 2, 3, 4, 5}, kFastSet{6, 7};

// MRIStep's evaluation counts per slow step for an explicit coupling table of s stages
// (SUNDIALS 6.4.1, arkode_mristep.c): f_slow at stages 1 .. s-2 and once after the step
// (arkCompleteStep's full RHS, reused as stage 0 of the next), plus one at the start; f_fast:
// the fast ERK's stages in every fast step (ceil(dc_i x ratio) steps for a stage of length
// dc_i h), once with every full RHS of MRIStep and once in the fast ARKStep's initial set-up.
struct ExpectedCounts {
  long slow_rhs, fast_steps, fast_rhs;
};
ExpectedCounts expected_counts(const std::string& table, const std::string& fast_table, int ratio, long steps) {
  MRIStepCoupling c = MRIStepCoupling_LoadTableByName(table.c_str());
  ARKodeButcherTable b = ARKodeButcherTable_LoadERKByName(fast_table.c_str());
  long per_step = 0;
  for (int i = 1; i < c->stages; ++i)
    if (c->c[i] > c->c[i - 1]) per_step += static_cast<long>(std::ceil((c->c[i] - c->c[i - 1]) * ratio - 1e-9));
  const ExpectedCounts e{1 + steps * (c->stages - 1), steps * per_step, steps * per_step * b->stages + steps + 2};
  MRIStepCoupling_Free(c);
  ARKodeButcherTable_Free(b);
  return e;
}

TEST(MriBookkeeping, EachLevelEvaluatesExactlyItsSet) {
  for (const std::string& table : mri_table_names()) {
    OscillatorEnsemble sys = ensemble();
    sys.record_calls = true;
    const std::vector<Real> y0 = excited_state(sys.n());
    const StepperOptions o = mri(0.05, 20, table);
    auto stepper = make_stepper(sys, o, 0, y0.data());
    std::vector<Real> y(y0.size());
    Real t = 0;
    ASSERT_EQ(stepper->advance(1.0, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
    const StepperStats s = stepper->stats();
    ASSERT_EQ(s.levels.size(), 2u);
    std::printf("%s: slow steps %ld rhs %ld particles %ld; fast steps %ld rhs %ld particles %ld; total %ld\n",
                table.c_str(), s.levels[0].steps, s.levels[0].rhs_evals, s.levels[0].particle_evals,
                s.levels[1].steps, s.levels[1].rhs_evals, s.levels[1].particle_evals, s.particle_evals);
    long slow_calls = 0, fast_calls = 0;
    for (const auto& call : sys.calls) {  // every call: exactly the slow or exactly the fast set
      const bool slow = call.active == kSlowSet, fast = call.active == kFastSet;
      EXPECT_TRUE(slow || fast) << "a call with " << call.active.size() << " particles at t=" << call.t;
      slow_calls += slow, fast_calls += fast;
    }
    EXPECT_EQ(slow_calls, s.levels[0].rhs_evals);
    EXPECT_EQ(fast_calls, s.levels[1].rhs_evals);
    EXPECT_EQ(s.steps, 20);  // 1.0 / 0.05
    const ExpectedCounts e = expected_counts(table, o.mri_fast_table, o.mri_ratio, s.steps);
    EXPECT_EQ(s.levels[0].rhs_evals, e.slow_rhs) << table;
    EXPECT_EQ(s.levels[1].steps, e.fast_steps) << table;
    EXPECT_EQ(s.levels[1].rhs_evals, e.fast_rhs) << table;
    EXPECT_EQ(s.levels[0].particle_evals, 6 * s.levels[0].rhs_evals);
    EXPECT_EQ(s.levels[1].particle_evals, 2 * s.levels[1].rhs_evals);
    EXPECT_EQ(s.particle_evals, s.levels[0].particle_evals + s.levels[1].particle_evals);  // the guard's count
    EXPECT_EQ(sys.full_calls, 0);  // every evaluation is a subset one
  }
}

TEST(MriBookkeeping, GlobalSteppersCountTheirParticlesPerRhsCall) {
  for (const std::string method : {"ARKODE_DORMAND_PRINCE_7_4_5", "leapfrog", "ARKODE_ZONNEVELD_5_3_4"}) {
    OscillatorEnsemble sys = ensemble();
    const std::vector<Real> y0 = excited_state(sys.n());
    StepperOptions o;
    o.method = method;
    if (method != "ARKODE_DORMAND_PRINCE_7_4_5") o.fixed_dt = 0.005;
    auto stepper = make_stepper(sys, o, 0, y0.data());
    std::vector<Real> y(y0.size());
    Real t = 0;
    ASSERT_EQ(stepper->advance(0.5, y.data(), t), AdvanceStatus::Reached) << method;
    const StepperStats s = stepper->stats();
    EXPECT_GT(s.rhs_evals, 0) << method;
    EXPECT_EQ(s.particle_evals, 8 * s.rhs_evals) << method;
    EXPECT_EQ(sys.full_calls, s.rhs_evals) << method;
  }
}

// A plain ODE without particles counts as one particle per RHS call.
class PlainOscillator : public OdeSystem {
 public:
  std::size_t size() const override { return 2; }
  int rhs(Real, const Real* y, Real* ydot) override {
    ydot[0] = y[1], ydot[1] = -y[0];
    return 0;
  }
};

TEST(MriBookkeeping, APlainOdeIsOneParticle) {
  PlainOscillator sys;
  const Real y0[] = {1, 0};
  StepperOptions o;
  auto stepper = make_stepper(sys, o, 0, y0);
  Real y[2], t = 0;
  ASSERT_EQ(stepper->advance(1.0, y, t), AdvanceStatus::Reached);
  EXPECT_EQ(stepper->stats().particle_evals, stepper->stats().rhs_evals);
  EXPECT_NE(format_stats(stepper->stats()).find("particle_evals="), std::string::npos);
}

// Particle 0 reports a fast stable step from t = 0.48 on: it joins the fast set at the end of
// the slow step landing on 0.5; calls before 0.5 see the old sets, calls after it the new ones.
TEST(MriBookkeeping, ARepartitionKeepsTheStateBitForBit) {
  const Real t1 = 0.5, t2 = 1.0;
  SwitchingEnsemble a_sys(0.48);
  a_sys.record_calls = true;
  const std::vector<Real> y0 = excited_state(a_sys.n());
  auto a = make_stepper(a_sys, mri(), 0, y0.data());
  std::vector<Real> y1(y0.size()), ya(y0.size()), yb(y0.size());
  Real t = 0;
  ASSERT_EQ(a->advance(t1, y1.data(), t), AdvanceStatus::Reached);
  ASSERT_EQ(a->advance(t2, ya.data(), t), AdvanceStatus::Reached);
  const std::vector<std::size_t> new_slow{1, 2, 3, 4, 5}, new_fast{0, 6, 7};
  long before = 0, after = 0;
  for (const auto& call : a_sys.calls) {
    if (call.t < t1 - 1e-12) {
      EXPECT_TRUE(call.active == kSlowSet || call.active == kFastSet) << "t=" << call.t;
      ++before;
    } else if (call.t > t1 + 1e-12) {
      EXPECT_TRUE(call.active == new_slow || call.active == new_fast) << "t=" << call.t;
      ++after;
    }
  }
  EXPECT_GT(before, 0);
  EXPECT_GT(after, 0);
  // A fresh stepper at (t1, y(t1)) with the new partition from its start takes the same steps.
  SwitchingEnsemble b_sys(0.48);
  auto b = make_stepper(b_sys, mri(), t1, y1.data());
  ASSERT_EQ(b->advance(t2, yb.data(), t), AdvanceStatus::Reached);
  for (std::size_t k = 0; k < ya.size(); ++k) EXPECT_EQ(ya[k], yb[k]) << "entry " << k;
}

// A restart at (t1, y(t1)) with the stepper's resume_data (its partition) takes the continued
// run's steps bit for bit; binned afresh it would not (particle 0 is held on the fast level
// by the hysteresis: stable step 1.1 h after being fast).
TEST(MriBookkeeping, ARestartCarriesThePartition) {
  const Real h = 0.05, t1 = 0.7, t2 = 1.0;
  // Advances to each of t_outs in turn (a time loop with an output at t1).
  auto run = [&](Real t0, const std::vector<Real>& y0, const std::vector<Real>& resume, std::vector<Real> t_outs,
                 std::vector<Real>* resume_out) {
    HystereticEnsemble sys(0.2, 0.4, 1.1 * h);
    StepperOptions o = mri(h);
    o.resume_data = resume;
    auto stepper = make_stepper(sys, o, t0, y0.data());
    std::vector<Real> y(y0.size());
    Real t = t0;
    for (Real t_end : t_outs) EXPECT_EQ(stepper->advance(t_end, y.data(), t), AdvanceStatus::Reached);
    if (resume_out) *resume_out = stepper->resume_data();
    return y;
  };
  const std::vector<Real> y0 = excited_state(8);
  std::vector<Real> resume;
  const std::vector<Real> y1 = run(0, y0, {}, {t1}, &resume);
  ASSERT_EQ(resume.size(), 8u + 16u);  // the levels, then the latest derivatives
  EXPECT_EQ(resume[0], 1);  // held fast by the hysteresis
  const std::vector<Real> y_continued = run(0, y0, {}, {t1, t2}, nullptr);
  const std::vector<Real> y_restarted = run(t1, y1, resume, {t2}, nullptr);
  const std::vector<Real> y_fresh = run(t1, y1, {}, {t2}, nullptr);
  for (std::size_t k = 0; k < y0.size(); ++k) EXPECT_EQ(y_restarted[k], y_continued[k]) << "entry " << k;
  EXPECT_NE(y_fresh, y_continued);  // the test can tell: without the partition the steps differ
}

TEST(MriBookkeeping, ResizeStartsMriStepAfreshAtTheNewState) {
  expect_resize_continues_as_fresh(ensemble, mri(), excited_state(8), 0.5, 1.0, 20);
}

TEST(MriBookkeeping, BadOptionsAreOneLineInvalidArguments) {
  OscillatorEnsemble sys = ensemble();
  const std::vector<Real> y0 = excited_state(sys.n());
  auto expect_error = [&](const StepperOptions& o, const std::string& what) { expect_invalid_argument(sys, o, y0, what); };
  StepperOptions o = mri();
  o.method = "mri-ARKODE_NO_SUCH_TABLE";
  expect_error(o, "method=mri-ARKODE_NO_SUCH_TABLE: unknown MRI coupling table");
  o = mri(0.05, 0);
  expect_error(o, "mri_ratio=0: must be >= 1");
  o = mri(0.0);
  expect_error(o, "set fixed_dt");
  o = mri();
  o.mri_fast_table = "RK4";
  expect_error(o, "mri_fast_table=RK4");
  o = mri();
  o.partition_hysteresis = -1;
  expect_error(o, "partition_hysteresis=-1");
  PlainOscillator plain;
  const Real p0[] = {1, 0};
  EXPECT_THROW(make_stepper(plain, mri(), 0, p0), std::invalid_argument);
}

TEST(MriBookkeeping, AFastStepAboveAParticlesStableStepIsRefused) {
  OscillatorEnsemble sys = ensemble();
  const std::vector<Real> y0 = excited_state(sys.n());
  try {
    make_stepper(sys, mri(0.05, 4), 0, y0.data());  // h / 4 = 0.0125 > 1 / 100
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("raise mri_ratio"), std::string::npos) << e.what();
  }
}

// An exception thrown by the system inside MRIStep's callbacks ends the run as Failed with its
// message (nothing crosses into SUNDIALS).
class ThrowingEnsemble : public OscillatorEnsemble {
 public:
  ThrowingEnsemble() : OscillatorEnsemble({1, 1, 1, 1, 1, 1, 100, 100}, 0.3) {}
  int rhs_subset(Real t, const Real* y, std::span<const std::size_t> active, Real* ydot) override {
    if (t > 0.3 && active.size() == 2) throw std::runtime_error("fast neighbour list exploded");
    return OscillatorEnsemble::rhs_subset(t, y, active, ydot);
  }
};

TEST(MriBookkeeping, AnExceptionInACallbackIsAFailureWithItsMessage) {
  ThrowingEnsemble sys;
  const std::vector<Real> y0 = excited_state(sys.n());
  auto stepper = make_stepper(sys, mri(), 0, y0.data());
  std::vector<Real> y(y0.size());
  Real t = 0;
  EXPECT_EQ(stepper->advance(1.0, y.data(), t), AdvanceStatus::Failed);
  EXPECT_NE(stepper->failure_reason().find("fast neighbour list exploded"), std::string::npos)
      << stepper->failure_reason();
  EXPECT_LE(t, 0.3 + 1e-12);
  EXPECT_GE(t, 0.25 - 1e-12);  // the last accepted slow step
}

}  // namespace
}  // namespace sphark::test
