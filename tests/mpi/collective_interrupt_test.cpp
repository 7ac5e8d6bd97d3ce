// The stop poll of a distributed run (StepperOptions::interrupt, issue #21): a signal reaches the
// ranks at different times, so the stepper reduces every poll over the ranks. One rank saying
// "stop" stops every rank at the same step; continuing afterwards reaches the end everywhere, the
// leapfrog with the serial run's state bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
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

void expect_collective_stop(StepperOptions opts) {
  Oscillators serial_sys(testing::block(kCount, 0, 1)), sys(testing::block(kCount, world().rank(), world().size()));
  opts.reproducible_norms = true;
  std::vector<Real> y_serial = serial_sys.initial_state(), y = sys.initial_state();
  Real t_serial = 0, t = 0;
  auto serial = make_stepper(serial_sys, opts, 0.0, y_serial.data());
  ASSERT_EQ(serial->advance(10, y_serial.data(), t_serial), AdvanceStatus::Reached);

  long polls = 0;
  const bool last = world().rank() == world().size() - 1;
  opts.communicator = world();
  opts.interrupt = [&] { return ++polls > 50 && last; };  // only the last rank ever says stop
  auto stepper = make_stepper(sys, opts, 0.0, y.data());
  const AdvanceStatus st = stepper->advance(10, y.data(), t);
  EXPECT_EQ(testing::ranks_failing(st != AdvanceStatus::Interrupted), 0);
  EXPECT_EQ(testing::global_max(t), -testing::global_max(-t));  // the same t on every rank
  EXPECT_EQ(testing::global_sum(polls), polls * world().size());  // every rank polled as often
  EXPECT_GT(t, 0);
  EXPECT_LT(t, 10);
  const Real t_stop = t;
  opts.interrupt = nullptr;  // (the stepper keeps its own copy: continue with it)
  polls = -1000000000;       // no rank says stop any more
  const AdvanceStatus more = stepper->advance(10, y.data(), t);
  EXPECT_EQ(testing::ranks_failing(more != AdvanceStatus::Reached), 0);
  EXPECT_EQ(t, 10);
  if (opts.method == "leapfrog") {  // continued as if never interrupted: the serial state bit for bit
    const std::vector<std::int64_t> ids = sys.ids(), all = serial_sys.ids();
    Real worst = 0;
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const std::size_t s = static_cast<std::size_t>(testing::slot(all, ids[i]));
      for (int part = 0; part < 2; ++part)
        worst = std::max(worst, std::abs(y[part * ids.size() + i] - y_serial[part * all.size() + s]));
    }
    EXPECT_EQ(testing::global_max(worst), 0.0);
  }
  if (world().rank() == 0) std::printf("%s: every rank stopped at t = %.6g, continued to t = 10\n", opts.method.c_str(), t_stop);
}

TEST(DistributedStepper, OneRanksInterruptStopsEveryRankAtTheSameStep) {
  StepperOptions erk;
  erk.rtol = 1e-8;
  erk.atol = {1e-10};
  expect_collective_stop(erk);
  StepperOptions lf;
  lf.method = "leapfrog";
  lf.fixed_dt = 0.01;
  expect_collective_stop(lf);
}

}  // namespace
}  // namespace sphark
