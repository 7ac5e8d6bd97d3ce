// Stepper::resize, serially (communicator of one rank without MPI) and distributed: removing
// one oscillator, or moving oscillators between ranks, keeps every surviving entry bit for bit
// in fixed-step runs (the entries are independent), keeps the leapfrog's next kick when its
// carried data moves along, and lets an adaptive run go on with the accuracy and step count of
// an uninterrupted one.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>

#include "mpi_env.hpp"
#include "oscillators.hpp"
#include "sphark/integrate/stepper.hpp"

namespace sphark {
namespace {

using testing::Oscillators;
using testing::world;

constexpr std::int64_t kCount = 29;

// The new local ids after the change at t_change: `drop` removed; with `rotate`, each rank's
// first oscillator goes to the next rank (appended there).
std::vector<std::int64_t> changed_ids(const Communicator& c, const std::vector<std::int64_t>& ids, std::int64_t drop,
                                      bool rotate) {
  std::vector<std::int64_t> out;
  for (std::size_t i = (rotate && c.size() > 1 && !ids.empty()) ? 1 : 0; i < ids.size(); ++i)
    if (ids[i] != drop) out.push_back(ids[i]);
  if (rotate && c.size() > 1) {
    const int prev = (c.rank() + c.size() - 1) % c.size();
    const std::vector<std::int64_t> prev_ids = testing::block(kCount, prev, c.size());
    if (!prev_ids.empty() && prev_ids.front() != drop) out.push_back(prev_ids.front());
  }
  return out;
}

// Values of the old state (or a full serial state) for oscillators `ids`: [x..., v...].
std::vector<Real> gather(const std::vector<Real>& y, const std::vector<std::int64_t>& from,
                         const std::vector<std::int64_t>& ids) {
  std::vector<Real> out(2 * ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const auto s = static_cast<std::size_t>(testing::slot(from, ids[i]));
    out[i] = y[s];
    out[ids.size() + i] = y[from.size() + s];
  }
  return out;
}

struct Result {
  std::vector<std::int64_t> ids;
  std::vector<Real> y;
  long steps_after = 0;  // steps taken after t_change
};

// Runs the oscillators of this rank (all of them with a serial communicator) to t_end; with
// change, at t_change the state is rebuilt for changed_ids and handed over by resize() (the
// leapfrog's carried data moves with its entries). In this single-process test every rank knows
// the whole uninterrupted serial state, so "moving" an oscillator takes its values from there.
Result run(StepperOptions o, const Communicator& c, bool change, bool rotate, bool carry, Real t_change, Real t_end,
           Real kappa = 0, bool stiff = false) {
  o.communicator = c;
  Oscillators sys(testing::block(kCount, c.rank(), c.size()), kappa, stiff);
  std::vector<Real> y = sys.initial_state();
  auto stepper = make_stepper(sys, o, 0.0, y.data());
  Real t = 0;
  stepper->advance(t_change, y.data(), t);
  const long steps_before = stepper->stats().steps;
  if (change) {
    // The full state and carried data at t_change, assembled from every rank's part.
    std::vector<Real> all(2 * kCount, 0.0), all_carried(2 * kCount, 0.0);
    const std::vector<Real> carried = stepper->carried_data();
    for (std::size_t i = 0; i < sys.count(); ++i)
      for (int part = 0; part < 2; ++part) {
        all[part * kCount + sys.ids()[i]] = y[part * sys.count() + i];
        if (!carried.empty()) all_carried[part * kCount + sys.ids()[i]] = carried[part * sys.count() + i];
      }
    c.allreduce(all.data(), all.size(), ReduceOp::Sum);  // each value once, others +0: exact
    c.allreduce(all_carried.data(), all_carried.size(), ReduceOp::Sum);
    sys.set_ids(changed_ids(c, sys.ids(), 5, rotate));
    std::vector<std::int64_t> every(kCount);
    for (std::int64_t k = 0; k < kCount; ++k) every[k] = k;
    y = gather(all, every, sys.ids());
    const std::vector<Real> new_carried = gather(all_carried, every, sys.ids());
    std::vector<Real> atol(y.size(), 1e-10);
    stepper->resize({y.data(), atol.data(), carry ? new_carried.data() : nullptr});
  }
  stepper->advance(t_end, y.data(), t);
  return {sys.ids(), y, stepper->stats().steps - steps_before};
}

// Count of entries differing in any bit from the uninterrupted serial run (all ranks).
std::int64_t bits_differing(const Result& r, const Result& serial) {
  const std::vector<Real> expected = gather(serial.y, serial.ids, r.ids);
  std::int64_t differ = 0;
  for (std::size_t k = 0; k < expected.size(); ++k)
    differ += std::bit_cast<std::uint64_t>(expected[k]) != std::bit_cast<std::uint64_t>(r.y[k]);
  return testing::global_sum(differ);
}

TEST(Resize, FixedStepErkKeepsTheSurvivorsBitForBit) {
  StepperOptions o;
  o.method = "ARKODE_DORMAND_PRINCE_7_4_5";
  o.fixed_dt = 0.01;
  const Result serial = run(o, Communicator{}, false, false, false, 2, 5);
  for (const Communicator& c : {Communicator{}, world()})
    for (bool rotate : {false, true}) {
      const Result r = run(o, c, true, rotate, false, 2, 5);
      EXPECT_EQ(bits_differing(r, serial), 0) << "distributed " << c.distributed() << " rotate " << rotate;
      EXPECT_EQ(c.allreduce(std::int64_t(r.ids.size()), ReduceOp::Sum), kCount - 1);
    }
}

// The implicit part is linear (ARKStepSetLinear): one Newton iteration per stage, per-entry
// arithmetic, so the survivors are again exact.
TEST(Resize, FixedStepImexKeepsTheSurvivorsBitForBit) {
  StepperOptions o;
  o.method = "ark-imex";
  o.fixed_dt = 0.01;
  const Result serial = run(o, Communicator{}, false, false, false, 2, 5, 50, true);
  for (const Communicator& c : {Communicator{}, world()})
    EXPECT_EQ(bits_differing(run(o, c, true, true, false, 2, 5, 50, true), serial), 0) << "distributed " << c.distributed();
}

// The leapfrog kicks with the derivative at its predictor: with the carried data moved along
// the resized run is the uninterrupted one bit for bit; re-evaluated at y it is not (the
// damping term depends on v), but stays within the method's error.
TEST(Resize, LeapfrogCarriedDataKeepsTheNextKick) {
  StepperOptions o;
  o.method = "leapfrog";
  o.fixed_dt = 0.01;
  const Result serial = run(o, Communicator{}, false, false, false, 2, 5, 0.3);
  for (const Communicator& c : {Communicator{}, world()}) {
    EXPECT_EQ(bits_differing(run(o, c, true, true, true, 2, 5, 0.3), serial), 0) << "distributed " << c.distributed();
    EXPECT_GT(bits_differing(run(o, c, true, true, false, 2, 5, 0.3), serial), 0);
  }
}

// Adaptive ERK: after removing oscillator 5 at t = 3 the run goes on with the step size it had
// (no restart from a small first step) and the accuracy of the uninterrupted run.
TEST(Resize, AdaptiveErkContinuesLikeAnUninterruptedRun) {
  StepperOptions o;
  o.rtol = 1e-8;
  o.atol = {1e-10};
  const Result whole = run(o, Communicator{}, false, false, false, 3, 10);
  auto error = [](const Result& r) {
    Real e = 0;
    for (std::size_t i = 0; i < r.ids.size(); ++i)
      e = std::max(e, std::abs(r.y[i] - testing::exact_x(r.ids[i], 10)));
    return testing::global_max(e);
  };
  for (const Communicator& c : {Communicator{}, world()}) {
    const Result r = run(o, c, true, true, false, 3, 10);
    const Real e = error(r), e_whole = error(whole);
    if (world().rank() == 0)
      std::printf("adaptive resize: error %.3g (uninterrupted %.3g), steps after %ld (uninterrupted %ld)\n", e, e_whole,
                  r.steps_after, whole.steps_after);
    EXPECT_LE(e, 2 * e_whole) << "distributed " << c.distributed();
    EXPECT_LE(r.steps_after, whole.steps_after + 2);
    EXPECT_GE(r.steps_after, whole.steps_after * 8 / 10);
  }
}

TEST(Resize, MissingPerEntryToleranceFailsOnEveryRank) {
  StepperOptions o;
  o.communicator = world();
  Oscillators sys(testing::block(kCount, world().rank(), world().size()));
  o.atol.assign(sys.size(), 1e-9);
  std::vector<Real> y = sys.initial_state();
  auto stepper = make_stepper(sys, o, 0.0, y.data());
  EXPECT_THROW(stepper->resize({y.data(), nullptr, nullptr}), std::invalid_argument);
}

}  // namespace
}  // namespace sphark
