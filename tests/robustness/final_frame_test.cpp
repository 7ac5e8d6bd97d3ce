// The time loop writes a VTK frame of the state it ends on (run/time_loop.cpp, finish()): when
// t_end is not a multiple of the frame interval, and when a hook ends the run early between frames
// (a sink taking the gas, say). On a grid that ends on t_end it adds nothing. One particle moving
// at unit speed, x(t) = t, so each frame's position is its time.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "sphark/run/time_loop.hpp"
#include "../support/temp_dir.hpp"

using namespace sphark;
using sphark::test::TempDir;

namespace {
class Drift final : public OdeSystem {  // x' = v, v' = 0
 public:
  Drift() : layout_(1) { layout_.add(Field::Position, 1).add(Field::Velocity, 1); }
  const StateLayout& layout() const { return layout_; }
  std::size_t size() const override { return 2; }
  const StateLayout* state_layout() const override { return &layout_; }
  int rhs(Real, const Real* y, Real* ydot) override {
    ydot[0] = y[1];
    ydot[1] = 0;
    return 0;
  }
  std::size_t position_offset() const override { return 0; }
  std::size_t velocity_offset() const override { return 1; }
  std::size_t position_size() const override { return 1; }

 private:
  StateLayout layout_;
};

// The times of the frames listed in <dir>/drift.pvd, in order.
std::vector<double> frame_times(const std::filesystem::path& dir) {
  std::ifstream in(dir / "drift.pvd");
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  std::vector<double> t;
  const std::string key = "timestep=\"";
  for (std::size_t at = s.find(key); at != std::string::npos; at = s.find(key, at + 1))
    t.push_back(std::stod(s.substr(at + key.size())));
  return t;
}

// Runs the drift to t_end with samples every 0.1 and frames every frame_every; end_after: a
// `finished` hook that ends the run at the first sample at or after that time (0: none).
std::vector<double> run(Real t_end, Real frame_every, Real end_after = 0) {
  TempDir dir;
  Drift sys;
  std::vector<Real> y0 = {0, 1}, x(1);
  StepperOptions o;
  o.method = "leapfrog";
  o.fixed_dt = 1.0 / 64;
  TimeLoopSettings s;
  s.program = "final_frame_test";
  s.t_end = t_end;
  s.sample_every = 0.1;
  s.frame_every = frame_every;
  s.frames_dir = dir.path();
  s.frames_basename = "drift";
  s.diagnostics_csv = dir.path() / "d.csv";
  s.columns = {"t"};
  s.quiet = true;
  TimeLoopHooks h;
  h.diagnostics = [](Real t, const Real*, const StepperStats&) { return std::vector<Real>{t}; };
  h.frame = [&](Real, const Real* y) {
    x[0] = y[0];
    return ParticleFrame{1, 1, x.data(), {}, nullptr};
  };
  if (end_after > 0) h.finished = [&](Real t) { return t >= end_after - 1e-12; };
  const TimeLoopResult r = run_time_loop(sys, sys.layout(), o, y0, s, h);
  EXPECT_TRUE(r.ok()) << r.failure;
  return frame_times(dir.path());
}
}  // namespace

TEST(FinalFrame, WrittenWhenTEndIsOffTheFrameGrid) {
  const std::vector<double> t = run(1.05, 0.5);  // frames at 0, 0.5, 1.0 on the grid, then the end
  ASSERT_EQ(t.size(), 4u);
  EXPECT_NEAR(t[2], 1.0, 1e-12);
  EXPECT_NEAR(t[3], 1.05, 1e-12);
}

TEST(FinalFrame, NotRepeatedWhenTheGridEndsOnTEnd) {
  const std::vector<double> t = run(1.0, 0.5);
  ASSERT_EQ(t.size(), 3u);
  EXPECT_NEAR(t[2], 1.0, 1e-12);
}

TEST(FinalFrame, WrittenWhenAHookEndsTheRunBetweenFrames) {
  const std::vector<double> t = run(2.0, 0.5, 0.7);  // ends at the sample t = 0.7
  ASSERT_EQ(t.size(), 3u);
  EXPECT_NEAR(t[1], 0.5, 1e-12);
  EXPECT_NEAR(t[2], 0.7, 1e-12);
}
