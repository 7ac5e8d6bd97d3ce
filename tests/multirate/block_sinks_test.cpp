// Block steps with a sink particle (issue #17; docs/time_integration.md, "Multirate"). A sink
// pulls on every gas particle, hardest on the closest ones, which orbit it on the shortest
// steps. Binned by a stable step of +inf it sat on level 0 and was kicked once per top step
// with a stale acceleration: in the gravitating sphere it drifted off and the gas's momentum
// jumped from 1e-6 to 2e-2 within one top step after sink formation. Its stable step is now the
// shortest gas step, so it is evaluated at every event of the cycle.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "sphark/integrate/forwarding_system.hpp"
#include "sphark/integrate/stepper.hpp"
#include "../support/sink_clump.hpp"

namespace sphark::test {
namespace {

// The active set of every rhs_subset call.
class RecordingSystem : public ForwardingSystem {
 public:
  using ForwardingSystem::ForwardingSystem;
  int rhs_subset(Real t, const Real* y, std::span<const std::size_t> active, Real* ydot) override {
    calls.emplace_back(active.begin(), active.end());
    return ForwardingSystem::rhs_subset(t, y, active, ydot);
  }
  std::vector<std::vector<std::size_t>> calls;
};

// One top step of 16 x the shortest gas step on the clump with a sink: the gas spreads over
// several levels, and the sink (the last particle) is in the active set of every evaluation.
TEST(BlockSinks, TheSinkIsEvaluatedAtEveryEvent) {
  Clump c = clump();
  SpmhdScheme<3>& s = *c.scheme;
  RecordingSystem sys(s);
  const Real shortest = s.max_stable_dt(0, c.y.data(), nullptr);
  ASSERT_GT(shortest, 0) << s.last_error();
  StepperOptions o;
  o.method = "leapfrog-blocks";
  o.max_dt = 16 * shortest;
  auto stepper = make_stepper(sys, o, 0, c.y.data());
  std::vector<Real> y(c.y.size());
  Real t = 0;
  ASSERT_EQ(stepper->advance(o.max_dt, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
  const StepperStats st = stepper->stats();
  std::size_t used = 0;
  for (const LevelStats& l : st.levels) used += l.rhs_evals > 0;
  EXPECT_GE(used, 3u) << "the gas should span several levels";
  ASSERT_EQ(sys.calls.size(), static_cast<std::size_t>(st.steps));  // one evaluation per event
  const std::size_t sink = s.num_particles() - 1;
  for (std::size_t k = 0; k < sys.calls.size(); ++k)
    EXPECT_TRUE(std::binary_search(sys.calls[k].begin(), sys.calls[k].end(), sink)) << "event " << k;
}

}  // namespace
}  // namespace sphark::test
