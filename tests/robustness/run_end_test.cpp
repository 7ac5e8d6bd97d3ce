// How the time loop ends a run (run/time_loop.cpp). It writes a VTK frame of the state it ends on
// (finish()): when t_end is not a multiple of the frame interval, and when a hook ends the run
// early between frames (a sink taking the gas, say); on a grid that ends on t_end it adds nothing.
// A hook that throws (a frame whose density solve fails, say) fails the run without losing what
// it has: the CSV rows so far and a checkpoint of the state reached (fail_in_hook()). One particle
// moving at unit speed, x(t) = t.
#include <gtest/gtest.h>

#include <algorithm>

#include "sphark/io/paraview_state.hpp"
#include "sphark/run/checkpoint.hpp"
#include "sphark/run/time_loop.hpp"
#include "../support/file_bytes.hpp"
#include "../support/temp_dir.hpp"

using namespace sphark;
using sphark::test::file_bytes;
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
  std::vector<double> t;
  for (const auto& [time, file] : read_pvd(dir / "drift.pvd")) t.push_back(time);
  return t;
}

struct Ending {
  TimeLoopResult result;
  std::vector<double> frame_times;
  std::string csv;  // the diagnostics file as written
};

// Runs the drift to t_end with samples every 0.1 and frames every frame_every; end_after: a
// `finished` hook that ends the run at the first sample at or after that time (0: none);
// throw_after: the frame hook throws from that time on (0: never).
// inject_nan_at: the RHS turns non-finite from then on (the stepper fails).
Ending run_to_end(const TempDir& dir, Real t_end, Real frame_every, Real end_after = 0, Real throw_after = 0,
                  Real inject_nan_at = 0) {
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
  s.checkpoint = dir.path() / "c.bin";
  s.quiet = true;
  s.inject_nan_at = inject_nan_at;
  TimeLoopHooks h;
  h.diagnostics = [](Real t, const Real*, const StepperStats&) { return std::vector<Real>{t}; };
  h.frame = [&](Real t, const Real* y) {
    if (throw_after > 0 && t >= throw_after - 1e-12) throw std::runtime_error("frame: density solve failed");
    x[0] = y[0];
    return ParticleFrame{1, 1, x.data(), {}, nullptr};
  };
  if (end_after > 0) h.finished = [&](Real t) { return t >= end_after - 1e-12; };
  const TimeLoopResult r = run_time_loop(sys, sys.layout(), o, y0, s, h);
  return {r, frame_times(dir.path()), file_bytes(s.diagnostics_csv)};
}

std::vector<double> run(Real t_end, Real frame_every, Real end_after = 0) {
  TempDir dir;
  const Ending e = run_to_end(dir, t_end, frame_every, end_after);
  EXPECT_TRUE(e.result.ok()) << e.result.failure;
  return e.frame_times;
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

TEST(HookFailure, KeepsTheRowsAndCheckpointsTheStateReached) {
  TempDir dir;
  const Ending e = run_to_end(dir, 2.0, 0.5, 0, 1.0);  // frames at 0 and 0.5; the one at 1.0 throws
  EXPECT_EQ(e.result.status, TimeLoopStatus::Failed);
  EXPECT_NE(e.result.failure.find("density solve failed"), std::string::npos) << e.result.failure;
  EXPECT_NEAR(e.result.t_reached, 1.0, 1e-12);
  EXPECT_EQ(e.frame_times.size(), 2u);
  // every row to t = 1.0 is in the file (the rows after the last frame were held in memory)
  EXPECT_EQ(std::count(e.csv.begin(), e.csv.end(), '\n'), 1 + 11) << e.csv;
  ASSERT_EQ(e.result.checkpoint, dir.path() / "c.bin");
  const Checkpoint c = load_checkpoint(e.result.checkpoint);
  EXPECT_NEAR(c.t, 1.0, 1e-12);
  EXPECT_NEAR(c.y[0], 1.0, 1e-12);  // x(t) = t
}

// A stepper failure whose last good state cannot be drawn: the stepper's reason stays the
// failure's (the frame's error is added), and the state is checkpointed all the same.
TEST(StepperFailure, KeepsItsReasonWhenTheLastGoodFrameFails) {
  TempDir dir;
  const Ending e = run_to_end(dir, 2.0, 2.0, 0, 0.3, 0.55);  // frames at 0 (and the end); NaN from 0.55
  EXPECT_EQ(e.result.status, TimeLoopStatus::Failed);
  const std::string& why = e.result.failure;
  const std::size_t added = why.find("; the last good state's row or frame: frame: density solve failed");
  ASSERT_NE(added, std::string::npos) << why;
  EXPECT_GT(added, 0u) << why;  // the stepper's reason comes first
  EXPECT_NE(why.substr(0, added).find("non-finite"), std::string::npos) << why;
  EXPECT_LT(e.result.t_reached, 0.56);
  ASSERT_EQ(e.result.checkpoint, dir.path() / "c.bin");
  EXPECT_NEAR(load_checkpoint(e.result.checkpoint).t, e.result.t_reached, 1e-12);
}
