// Issue #14, item 5: every callback is a function of (t, y). An adaptive, CFL-capped run that is
// restarted from a checkpoint must cap its first step exactly as the uninterrupted run capped the
// same step: before the fix, the force criterion of WCSPH read the acceleration left by the last
// rhs() call, which a freshly built system (a restart) does not have, so the first step after a
// restart ran with the Courant limit alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "sphark/run/time_loop.hpp"
#include "sphark/operators/tait_eos.hpp"
#include "sphark/scenes/water_drop/water_drop.hpp"
#include "sphark/schemes/wcsph/wcsph_system.hpp"
#include "../support/temp_dir.hpp"
#include "quiet_loop.hpp"

using namespace sphark;
using sphark::test::TempDir;

namespace {

// Forwards to the scheme and records what the stepper asked: every max_stable_dt(t, y, null)
// (the adaptive cap, taken at the start of every output interval) and every RHS time.
class Probe final : public OdeSystem {
 public:
  explicit Probe(OdeSystem& inner) : inner_(inner) {}
  std::size_t size() const override { return inner_.size(); }
  const StateLayout* state_layout() const override { return inner_.state_layout(); }
  int rhs(Real t, const Real* y, Real* ydot) override {
    rhs_times.push_back(t);
    return inner_.rhs(t, y, ydot);
  }
  std::size_t position_offset() const override { return inner_.position_offset(); }
  std::size_t velocity_offset() const override { return inner_.velocity_offset(); }
  std::size_t position_size() const override { return inner_.position_size(); }
  Real max_stable_dt(Real t, const Real* y, const Real* ydot) override {
    const Real dt = inner_.max_stable_dt(t, y, ydot);
    if (!ydot) caps.emplace_back(t, dt);
    return dt;
  }
  std::vector<std::pair<Real, Real>> caps;
  std::vector<Real> rhs_times;

 private:
  OdeSystem& inner_;
};

// A small drop whose force criterion cfl sqrt(h/|a|) is below its Courant criterion
// cfl h/(c + |v|): started at rho0 everywhere (no pressure gradient to balance the body force:
// |a| = omega^2 r at first), slow sound (c = 10).
WaterDropConfig force_limited_drop() {
  WaterDropConfig c;
  c.spacing = 0.2;
  c.amplitude = 10;
  c.sound_speed = 10;
  c.exact_initial_pressure = false;
  c.cleaning = false;
  c.delta = 0;
  c.cfl = 0.25;
  return c;
}

struct CappedRun {
  std::vector<std::pair<Real, Real>> caps;
  std::vector<Real> rhs_times;
};

CappedRun capped_run(const WaterDropConfig& config, Real t_end, const std::filesystem::path& dir, const Checkpoint* restart) {
  WaterDrop drop = make_water_drop(config);
  Probe probe(drop.model->system());
  StepperOptions o;
  o.method = "ARKODE_BOGACKI_SHAMPINE_4_2_3";
  o.rtol = 1e-3;  // loose: the step wants to grow beyond the cap
  o.atol = water_drop_absolute_tolerances(drop, 1e-3);
  const TimeLoopSettings s = sphark::test::quiet_loop("restart_cap_test", t_end, 2e-4, 4e-4, dir, restart);
  const TimeLoopHooks h = sphark::test::time_column();
  const TimeLoopResult r = run_time_loop(probe, drop.model->layout(), o, drop.y0, s, h);
  EXPECT_TRUE(r.ok()) << r.failure;
  return {probe.caps, probe.rhs_times};
}

}  // namespace

TEST(RestartCap, TheFirstStepAfterARestartIsCappedAsInTheUninterruptedRun) {
  const WaterDropConfig config = force_limited_drop();
  TempDir whole_dir, first_dir, second_dir;
  const CappedRun whole = capped_run(config, 8e-4, whole_dir.path(), nullptr);
  capped_run(config, 4e-4, first_dir.path(), nullptr);
  const Checkpoint c = load_checkpoint(first_dir.path() / "checkpoint.bin");
  ASSERT_EQ(c.t, 4e-4);
  const CappedRun second = capped_run(config, 8e-4, second_dir.path(), &c);

  // The restarted run's first cap (the first call of the adaptive run; the time loop's min_dt
  // scale asks first, at the same state) equals the uninterrupted run's cap at t = 4e-4, bit for bit.
  ASSERT_FALSE(second.caps.empty());
  EXPECT_EQ(second.caps.front().first, c.t);
  const auto same_time = std::find_if(whole.caps.begin(), whole.caps.end(), [&](const auto& p) { return p.first == c.t; });
  ASSERT_NE(same_time, whole.caps.end());
  EXPECT_EQ(second.caps.front().second, same_time->second);

  // ... and the force criterion is the one that binds there: the cap is below the Courant limit.
  WaterDrop probe = make_water_drop(config);
  const auto v = vector_field<2>(c.y.data(), probe.model->layout(), Field::Velocity);
  const auto rho = scalar_field(c.y.data(), probe.model->layout(), Field::Density);
  Real vmax = 0, cmax = 0;
  for (Index a = 0; a < v.cols(); ++a) {
    vmax = std::max(vmax, v.col(a).norm());
    cmax = std::max(cmax, tait_sound_speed(rho[a], config.rho0, config.sound_speed));
  }
  const Real h = config.h_factor * config.spacing;
  const Real courant = config.cfl * h / (cmax + vmax);  // alpha = 0: no viscous signal term
  EXPECT_LT(second.caps.front().second, 0.9 * courant);


  // The first step after the restart stays within the cap (Bogacki-Shampine's last stage is at t + dt).
  std::vector<Real> after;
  for (Real t : second.rhs_times)
    if (t > c.t) after.push_back(t);
  ASSERT_GE(after.size(), 3u);
  EXPECT_LE(after[2] - c.t, second.caps.front().second * (1 + 1e-12));
}
