// gravitating_sphere end to end through the shared run driver: a restart continues the
// uninterrupted run bit for bit, before and after a sink forms (the cold collapse, 400
// particles). What a restart must carry besides the state: the leapfrog's derivative
// (Stepper::resume_data) and the h each density solve starts from (OdeSystem::resume_data); and
// the scheme's sums must not depend on when its neighbour lists were last built (the gravity
// sees the particles in state order).
#include <gtest/gtest.h>

#include <cstring>

#include "../support/bit_equal.hpp"
#include "../support/temp_dir.hpp"
#include "run_example.hpp"
#include "split_run.hpp"
#include "sphark/run/checkpoint.hpp"
#include "sphark/run/time_loop.hpp"

using namespace sphark;
using namespace sphark::test;

namespace {
using Args = std::vector<std::string>;

Args sphere(const std::string& sinks) {
  return {"--particles", "400", "--sinks", sinks, "--output-every", "0.01", "--checkpoint-every", "0.01", "--no-render",
          "--threads", "1"};
}

void expect_same_continuation(const Checkpoint& whole, const Checkpoint& restarted) {
  EXPECT_EQ(whole.t, restarted.t);
  EXPECT_EQ(whole.species, restarted.species);
  EXPECT_TRUE(bit_equal(whole.y, restarted.y));
  EXPECT_TRUE(bit_equal(whole.stepper_data, restarted.stepper_data));
  EXPECT_TRUE(bit_equal(whole.system_data, restarted.system_data));
  EXPECT_EQ(whole.system_data.size(), 2 * whole.particles() + 1);  // h and div v per gas particle, the time of h
  EXPECT_EQ(whole.text("diagnostics.csv"), restarted.text("diagnostics.csv"));  // every row, every digit
}
}  // namespace

TEST(GravityRuns, RestartOfTheCollapseIsBitForBit) {
  TempDir dir;
  Checkpoint whole, restarted;
  ASSERT_TRUE(split_run("gravitating_sphere", sphere("off"), dir.path(), "gas", "uniform/checkpoint.bin", whole,
                        restarted, "0.5", "0.6"));
  expect_same_continuation(whole, restarted);
  // the restart wrote into another --out: its series lists every frame of the run, the earlier
  // ones where the first run wrote them, and each listed file opens
  const std::filesystem::path second = dir.path() / "gas_second" / "uniform";
  const std::vector<std::string> files = pvd_files(second / "sphere.pvd");
  EXPECT_EQ(files.size(), pvd_files(dir.path() / "gas_whole" / "uniform" / "sphere.pvd").size());
  ASSERT_FALSE(files.empty());
  EXPECT_EQ(files.front(), "../../gas_first/uniform/sphere_00000.vtp");
  for (const std::string& f : files) EXPECT_TRUE(std::filesystem::exists(second / f)) << f;
}

TEST(GravityRuns, RestartWithASinkIsBitForBit) {
  TempDir dir;
  Checkpoint whole, restarted;
  ASSERT_TRUE(split_run("gravitating_sphere", sphere("on"), dir.path(), "sinks", "uniform/checkpoint.bin", whole,
                        restarted, "1.12", "1.14"));
  // the restart happens with a sink in the state, and the sink goes on accreting after it
  const Checkpoint split = load_checkpoint(dir.path() / "sinks_first" / "uniform" / "checkpoint.bin");
  ASSERT_EQ(split.species.size(), 2u);
  EXPECT_GE(split.species[1].particles, 1u);
  EXPECT_LT(whole.particles(), split.particles());
  expect_same_continuation(whole, restarted);
}

// The magnetised collapse on block steps (1,450 particles, 0.02 -> 0.04 t_ff): every column of
// diagnostics.csv to every digit, the momentum budget's split included (its tensile part was
// summed in slot order, which a restart's list builds renumber: it differed in the 10th digit).
TEST(GravityRuns, RestartOfTheMagnetisedCollapseOnBlockStepsIsBitForBit) {
  TempDir dir;
  Checkpoint whole, restarted;
  ASSERT_TRUE(split_run("cloud_collapse",
                        {"--particles", "1000", "--stepper", "leapfrog-blocks", "--max-dt", "0.005", "--output-every",
                         "0.01", "--checkpoint-every", "0.02", "--no-render", "--threads", "1"},
                        dir.path(), "collapse", "cleaning_resistivity/checkpoint.bin", whole, restarted, "0.02", "0.04"));
  EXPECT_EQ(whole.t, restarted.t);
  EXPECT_TRUE(bit_equal(whole.y, restarted.y));
  EXPECT_TRUE(bit_equal(whole.stepper_data, restarted.stepper_data));
  EXPECT_EQ(whole.text("diagnostics.csv"), restarted.text("diagnostics.csv"));
}

// --opening mass reaches the tree: the checkpoint's scene names it with its default root angle
// 0.35 and the run differs from the fixed angle's; a restart keeps it (the stored options), and
// one that asks for the fixed angle is refused (exit 2: other scene parameters).
TEST(GravityRuns, MassDependentOpeningIsRecordedAndChecked) {
  TempDir dir;
  const std::filesystem::path fixed = dir.path() / "fixed", mass = dir.path() / "mass";
  const auto with = [](Args more) {
    Args a = sphere("off");
    a.insert(a.end(), {"--t-end", "0.05"});
    a.insert(a.end(), more.begin(), more.end());
    return a;
  };
  ASSERT_EQ(run(require_example("gravitating_sphere"), with({"--out", fixed.string()}), dir.path()).exit_code, 0);
  const Finished m = run(require_example("gravitating_sphere"), with({"--out", mass.string(), "--opening", "mass"}),
                         dir.path());
  ASSERT_EQ(m.exit_code, 0) << m.err;
  const std::filesystem::path ckpt = mass / "uniform" / "checkpoint.bin";
  const Checkpoint a = load_checkpoint(fixed / "uniform" / "checkpoint.bin"), b = load_checkpoint(ckpt);
  EXPECT_EQ(a.text("scene").find("opening"), std::string::npos);  // a fixed run's text is as before
  EXPECT_NE(b.text("scene").find("opening=mass"), std::string::npos) << b.text("scene");
  EXPECT_NE(b.text("scene").find("theta=0.35"), std::string::npos) << b.text("scene");
  EXPECT_EQ(a.t, b.t);
  EXPECT_FALSE(bit_equal(a.y, b.y));
  const auto restart = [&](Args more, const char* out) {
    Args r{"--restart", ckpt.string(), "--out", (dir.path() / out).string(), "--t-end", "0.06"};
    r.insert(r.end(), more.begin(), more.end());
    return run(require_example("gravitating_sphere"), r, dir.path());
  };
  const Finished kept = restart({}, "kept");
  ASSERT_EQ(kept.exit_code, 0) << kept.err;
  EXPECT_EQ(load_checkpoint(dir.path() / "kept" / "uniform" / "checkpoint.bin").text("scene"), b.text("scene"));
  const Finished refused = restart({"--opening", "fixed"}, "refused");
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_NE(refused.err.find("scene parameters"), std::string::npos) << refused.err;
}
