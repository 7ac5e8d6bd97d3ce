// Steppers on a distributed state: independent oscillators split in blocks over the ranks run
// with exactly the step sequence of the serial run of all of them (global reproducible norms,
// CFL limit and roots reduced over the ranks) and give its results bit for bit; against
// SUNDIALS' plain sequential norm they agree within the tolerance; one rank's failure reaches
// every rank, with its message.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "mpi_env.hpp"
#include "oscillators.hpp"
#include "sphark/integrate/stepper.hpp"

namespace sphark {
namespace {

using testing::Oscillators;
using testing::world;

constexpr std::int64_t kCount = 37;

struct RunResult {  // one run's end
  std::vector<Real> y;  // final state over `ids`
  std::vector<std::int64_t> ids;
  StepperStats stats;
  AdvanceStatus status = AdvanceStatus::Reached;
  Real t = 0;
  std::string failure;
  std::vector<int> roots;
};

// Runs `sys` from its exact initial state to t_end in output intervals of 1.
RunResult run(Oscillators& sys, StepperOptions opts, const Communicator& comm, Real t_end) {
  opts.communicator = comm;
  RunResult r;
  r.y = sys.initial_state();
  r.ids = sys.ids();
  auto stepper = make_stepper(sys, opts, 0.0, r.y.data());
  for (Real t_out = 1; t_out <= t_end && r.status == AdvanceStatus::Reached; t_out += 1)
    r.status = stepper->advance(t_out, r.y.data(), r.t);
  r.stats = stepper->stats();
  r.failure = stepper->failure_reason();
  r.roots = stepper->roots_found();
  return r;
}

// Largest |distributed - serial| / max(1, |serial|) over this rank's entries, over all ranks.
Real max_difference(const RunResult& dist, const RunResult& serial) {
  const std::size_t n = dist.ids.size(), ns = serial.ids.size();
  Real worst = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t s = static_cast<std::size_t>(testing::slot(serial.ids, dist.ids[i]));
    for (int part = 0; part < 2; ++part) {
      const Real a = dist.y[part * n + i], b = serial.y[part * ns + s];
      worst = std::max(worst, std::abs(a - b) / std::max(1.0, std::abs(b)));
    }
  }
  return testing::global_max(worst);
}

void expect_same_steps(const RunResult& dist, const RunResult& serial) {
  EXPECT_EQ(dist.stats.steps, serial.stats.steps);
  EXPECT_EQ(dist.stats.attempts, serial.stats.attempts);
  EXPECT_EQ(dist.stats.rhs_evals, serial.stats.rhs_evals);
  EXPECT_EQ(dist.stats.error_test_failures, serial.stats.error_test_failures);
  EXPECT_EQ(dist.status, serial.status);
  EXPECT_EQ(dist.t, serial.t);
}

RunResult compare(StepperOptions opts, Real kappa, bool stiff, std::int64_t count = kCount, Real* difference = nullptr) {
  Oscillators serial_sys(testing::block(count, 0, 1), kappa, stiff), dist_sys(testing::block(count, world().rank(), world().size()), kappa, stiff);
  opts.reproducible_norms = true;  // the distributed run's norm (always on with MPI; also without)
  const RunResult serial = run(serial_sys, opts, Communicator{}, 10);
  const RunResult dist = run(dist_sys, opts, world(), 10);
  expect_same_steps(dist, serial);
  const Real diff = max_difference(dist, serial);
  if (difference) *difference = diff;
  if (world().rank() == 0) std::printf("%s: %ld steps, max difference to serial %.3g\n", opts.method.c_str(), dist.stats.steps, diff);
  return dist;
}

// With the reproducible norm the steps are the serial ones, and every other vector operation
// is the same per-entry arithmetic on the serial and the parallel vector: bit for bit.
constexpr Real kBitForBit = 0;

TEST(DistributedStepper, AdaptiveErkTakesTheSerialSteps) {
  StepperOptions o;
  o.rtol = 1e-8;
  o.atol = {1e-10};
  Real diff = 1;
  const RunResult r = compare(o, 0, false, kCount, &diff);
  EXPECT_LE(diff, kBitForBit);
  EXPECT_GT(r.stats.steps, 100);
}

// Against SUNDIALS' own sequential norm the step sequences part where round-off first tips an
// accept/reject decision; both runs stay within their tolerance of each other.
TEST(DistributedStepper, AdaptiveErkAgreesWithThePlainSerialNormWithinTolerance) {
  StepperOptions o;
  o.rtol = 1e-8;
  o.atol = {1e-10};
  Oscillators s(testing::block(kCount, 0, 1)), d(testing::block(kCount, world().rank(), world().size()));
  const RunResult serial = run(s, o, Communicator{}, 10), dist = run(d, o, world(), 10);
  const Real diff = max_difference(dist, serial);
  EXPECT_LE(diff, 100 * o.rtol);
  EXPECT_NEAR(double(dist.stats.steps), double(serial.stats.steps), 0.05 * serial.stats.steps);
  if (world().rank() == 0)
    std::printf("plain serial norm: %ld steps, distributed: %ld steps, max difference %.3g\n", serial.stats.steps,
                dist.stats.steps, diff);
}

TEST(DistributedStepper, AdaptiveErkPerEntryTolerances) {
  StepperOptions o;
  o.rtol = 1e-7;
  o.method = "ARKODE_VERNER_8_5_6";
  o.reproducible_norms = true;
  Oscillators s(testing::block(kCount, 0, 1)), d(testing::block(kCount, world().rank(), world().size()));
  auto atol_of = [](const std::vector<std::int64_t>& ids) {
    std::vector<Real> a;
    for (int part = 0; part < 2; ++part)
      for (auto k : ids) a.push_back(1e-10 * (1 + k % 3 + part));
    return a;
  };
  o.atol = atol_of(s.ids());
  const RunResult serial = run(s, o, Communicator{}, 10);
  o.atol = atol_of(d.ids());
  const RunResult dist = run(d, o, world(), 10);
  expect_same_steps(dist, serial);
  EXPECT_LE(max_difference(dist, serial), kBitForBit);
}

TEST(DistributedStepper, ImexTakesTheSerialSteps) {
  StepperOptions o;
  o.method = "ark-imex";
  o.rtol = 1e-7;
  Real diff = 1;
  compare(o, 200.0, true, kCount, &diff);  // damping rate 200: stiff, implicit
  EXPECT_LE(diff, kBitForBit);
}

TEST(DistributedStepper, LeapfrogCflStepIsTheSerialBitForBit) {
  StepperOptions o;
  o.method = "leapfrog";
  o.cfl_safety = 0.3;  // dt = 0.3 min_k 0.5 / w_k: the minimum is on one rank only
  Real diff = 1;
  compare(o, 0.1, false, kCount, &diff);
  EXPECT_EQ(diff, 0.0);
}

// Every root event (time and direction of each g_k) up to t = 10, advancing on after each.
std::vector<std::pair<Real, std::vector<int>>> root_events(Oscillators& sys, const Communicator& comm) {
  StepperOptions o;
  o.rtol = 1e-9;
  o.reproducible_norms = true;
  o.root_reduction = {ReduceOp::Min, ReduceOp::Max, ReduceOp::Sum};
  o.communicator = comm;
  std::vector<Real> y = sys.initial_state();
  auto stepper = make_stepper(sys, o, 0.0, y.data());
  std::vector<std::pair<Real, std::vector<int>>> events;
  Real t = 0;
  for (Real t_out = 1; t_out <= 10;) {
    const AdvanceStatus s = stepper->advance(t_out, y.data(), t);
    if (s == AdvanceStatus::RootFound) events.emplace_back(t, stepper->roots_found());
    else if (s == AdvanceStatus::Reached) t_out += 1;
    else break;
  }
  return events;
}

TEST(DistributedStepper, RootsAreReducedOverTheRanks) {
  Oscillators s(testing::block(kCount, 0, 1)), d(testing::block(kCount, world().rank(), world().size()));
  s.enable_roots(kCount);
  d.enable_roots(kCount);
  d.set_total_share(world().rank() == 0);
  const auto serial = root_events(s, Communicator{}), dist = root_events(d, world());
  ASSERT_GE(serial.size(), 3u);  // each g_k crosses at least once
  ASSERT_EQ(dist.size(), serial.size());
  for (std::size_t e = 0; e < serial.size(); ++e) {
    EXPECT_EQ(dist[e].second, serial[e].second) << "event " << e;
    EXPECT_NEAR(dist[e].first, serial[e].first, 1e-12 * serial[e].first) << "event " << e;
  }
}

TEST(DistributedStepper, EmptyRanksTakePart) {
  for (const char* method : {"ARKODE_DORMAND_PRINCE_7_4_5", "leapfrog"}) {
    StepperOptions o;
    o.method = method;
    Real diff = 1;
    compare(o, 0, false, 3, &diff);  // 3 oscillators: on 4 ranks one holds none
    EXPECT_LE(diff, kBitForBit) << method;
  }
}

// A fatal failure on the last rank: every rank stops at the same last good state, and every
// rank's failure_reason() names that rank and its message.
TEST(DistributedStepper, OneRanksFailureEndsEveryRankWithItsMessage) {
  StepperOptions o;
  Oscillators d(testing::block(kCount, world().rank(), world().size()));
  const int last = world().size() - 1;
  if (world().rank() == last) d.fail_after(2.5, 0);  // throws
  const RunResult dist = run(d, o, world(), 10);
  EXPECT_EQ(dist.status, AdvanceStatus::Failed);
  const std::string expected =  // serial: the stepper's own report of the exception
      world().distributed() ? "rank " + std::to_string(last) + ": rhs: oscillator blew up" : "oscillator blew up";
  EXPECT_NE(dist.failure.find(expected), std::string::npos) << dist.failure;
  EXPECT_EQ(world().allreduce(dist.t, ReduceOp::Min), world().allreduce(dist.t, ReduceOp::Max));
  EXPECT_LE(dist.t, 2.5);
}

// A recoverable failure on one rank is retried on all, as in the serial run that fails once.
TEST(DistributedStepper, RecoverableFailureOnOneRankIsRetriedEverywhere) {
  for (const char* method : {"ARKODE_DORMAND_PRINCE_7_4_5", "leapfrog"}) {
    StepperOptions o;
    o.method = method;
    o.reproducible_norms = true;
    Oscillators s(testing::block(kCount, 0, 1)), d(testing::block(kCount, world().rank(), world().size()));
    s.fail_after(2.5, 1);
    if (world().rank() == world().size() - 1) d.fail_after(2.5, 1);
    const RunResult serial = run(s, o, Communicator{}, 10), dist = run(d, o, world(), 10);
    EXPECT_EQ(serial.stats.rhs_recoveries, 1) << method;
    EXPECT_EQ(dist.stats.rhs_recoveries, 1) << method;
    expect_same_steps(dist, serial);
    EXPECT_LE(max_difference(dist, serial), kBitForBit) << method;
  }
}

TEST(DistributedStepper, BadOptionOnOneRankFailsOnEveryRank) {
  StepperOptions o;
  Oscillators d(testing::block(kCount, world().rank(), world().size()));
  if (world().rank() == world().size() - 1) o.rtol = -1;
  o.communicator = world();
  std::vector<Real> y = d.initial_state();
  try {
    make_stepper(d, o, 0, y.data());
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("rtol=-1: must be > 0"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sphark
