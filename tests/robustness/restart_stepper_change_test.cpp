// A restart that changes the stepper (`--restart ... --stepper OTHER`): the checkpoint's stepper
// data (Stepper::resume_data: the leapfrog's derivative, the block steps' levels, MRIStep's
// partition) belongs to the stepper that wrote it. It is dropped, and the new stepper starts
// afresh at the checkpoint's state — exactly as from the same checkpoint without stepper data —
// while a restart with the same stepper still continues bit for bit.
#include <gtest/gtest.h>

#include <string>

#include "../support/bit_equal.hpp"
#include "../support/temp_dir.hpp"
#include "quiet_loop.hpp"
#include "sphark/run/checkpoint.hpp"
#include "sphark/run/time_loop.hpp"
#include "sphark/scenes/water_drop/water_drop.hpp"

using namespace sphark;
using sphark::test::bit_equal;
using sphark::test::TempDir;

namespace {

// The small WCSPH drop (spacing 0.2) to t_end with `method`, a checkpoint at the end; returns it.
Checkpoint drop_run(const std::string& method, Real t_end, const std::filesystem::path& dir, const Checkpoint* restart) {
  WaterDropConfig config;
  config.spacing = 0.2;
  config.cleaning = false;
  WaterDrop drop = make_water_drop(config);
  StepperOptions o;
  o.method = method;
  o.max_dt = 1e-4;  // the block steps' top step (a bound for the leapfrog)
  const TimeLoopSettings s = test::quiet_loop("restart_stepper_change_test", t_end, 4e-4, 4e-4, dir, restart);
  const TimeLoopHooks h = test::time_column();
  const TimeLoopResult r = run_time_loop(drop.model->system(), drop.model->layout(), o, drop.y0, s, h);
  EXPECT_TRUE(r.ok()) << r.failure;
  return load_checkpoint(dir / "checkpoint.bin");
}

}  // namespace

TEST(RestartStepperChange, ANewStepperStartsAfreshAtTheCheckpointState) {
  TempDir first, changed, stripped_dir, same, whole;
  const Checkpoint c = drop_run("leapfrog-blocks", 4e-4, first.path(), nullptr);
  ASSERT_EQ(c.text("stepper"), "leapfrog-blocks");
  ASSERT_FALSE(c.stepper_data.empty());
  for (const std::string other : {"leapfrog", "mri-ARKODE_MIS_KW3"}) {
    SCOPED_TRACE(other);
    const Checkpoint a = drop_run(other, 8e-4, changed.path(), &c);  // (the blocks' data would not fit)
    Checkpoint without = c;
    without.stepper_data.clear();
    const Checkpoint b = drop_run(other, 8e-4, stripped_dir.path(), &without);
    EXPECT_EQ(a.t, 8e-4);
    EXPECT_EQ(a.text("stepper"), other);
    EXPECT_TRUE(bit_equal(a.y, b.y));
    EXPECT_TRUE(bit_equal(a.stepper_data, b.stepper_data));
  }
  // the same stepper: its data carries over, the uninterrupted run bit for bit
  const Checkpoint continued = drop_run("leapfrog-blocks", 8e-4, same.path(), &c);
  const Checkpoint uninterrupted = drop_run("leapfrog-blocks", 8e-4, whole.path(), nullptr);
  EXPECT_TRUE(bit_equal(continued.y, uninterrupted.y));
}
