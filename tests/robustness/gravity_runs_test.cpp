// gravitating_sphere end to end through the shared run driver: a restart continues the
// uninterrupted run bit for bit, before and after a sink forms (the cold collapse, 400
// particles). What a restart must carry besides the state: the leapfrog's derivative
// (Stepper::resume_data) and the h each density solve starts from (OdeSystem::resume_data); and
// the scheme's sums must not depend on when its neighbour lists were last built (the gravity
// sees the particles in state order).
#include <gtest/gtest.h>

#include <cstring>

#include "../support/temp_dir.hpp"
#include "run_example.hpp"
#include "split_run.hpp"
#include "sphark/run/checkpoint.hpp"
#include "sphark/run/time_loop.hpp"

using namespace sphark;
using namespace sphark::test;

namespace {
using Args = std::vector<std::string>;

bool bit_equal(const std::vector<Real>& a, const std::vector<Real>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Real)) == 0;
}

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
  EXPECT_EQ(whole.system_data.size(), whole.particles());  // one h per gas particle
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
