// The per-particle steppers (`leapfrog-blocks`, `mri-<table>`; issue #17) through the example
// drivers: offered on every example whose system evaluates particle subsets (the Orszag-Tang
// vortex included), refused at parse time where they cannot run or lack their top step, and
// --max-dt read in the scene's time unit (the collapse's t_ff) like every other time option.
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

// exit 2, one line on stderr holding `expect`, nothing written
void expect_refused(const std::string& program, const Args& args, const std::string& expect) {
  TempDir dir;
  const auto out = dir.path() / "out";
  Args all = args;
  all.insert(all.end(), {"--out", out.string(), "--no-render"});
  const Finished f = run(require_example(program), all, dir.path());
  EXPECT_EQ(f.exit_code, 2) << program;
  EXPECT_NE(f.err.find(expect), std::string::npos) << f.err;
  EXPECT_EQ(std::count(f.err.begin(), f.err.end(), '\n'), 1) << f.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// The steps column's last value of <out>/<run>/diagnostics.csv.
Real steps_of(const std::filesystem::path& run_dir) {
  const std::vector<Real> steps = csv_column(slurp(run_dir / "diagnostics.csv"), "steps");
  return steps.empty() ? -1 : steps.back();
}
}  // namespace

// The vortex (2D SPMHD, periodic) on block steps and on MRIStep: a restart continues the
// uninterrupted run bit for bit (the checkpoint carries the levels / the partition).
TEST(PerParticleSteppers, OrszagTangRunsOnBlockStepsAndMriAndRestartsBitForBit) {
  TempDir dir;
  for (const std::string stepper : {"leapfrog-blocks", "mri-ARKODE_MRI_GARK_ERK33a"}) {
    SCOPED_TRACE(stepper);
    const Args opts = {"--nx", "8", "--variant", "cleaning", "--no-render", "--threads", "1", "--stepper", stepper,
                       "--max-dt", "0.01", "--output-every", "0.05", "--checkpoint-every", "0.1"};
    Checkpoint whole, restarted;
    ASSERT_TRUE(split_run("orszag_tang", opts, dir.path(), stepper, "cleaning/checkpoint.bin", whole, restarted));
    EXPECT_EQ(whole.t, restarted.t);
    EXPECT_NEAR(whole.t, 0.2, 1e-12);
    EXPECT_TRUE(bit_equal(whole.y, restarted.y));
    EXPECT_TRUE(bit_equal(whole.stepper_data, restarted.stepper_data));
    // every diagnostics column to every digit; a restarted MRIStep evaluates its starting state
    // once more (a fresh ARKODE integrator), the block steps carry theirs in the checkpoint
    const std::string a = whole.text("diagnostics.csv"), b = restarted.text("diagnostics.csv");
    for (const std::string column : {"t", "mean_h_divB_over_B", "max_h_divB_over_B", "kinetic_energy", "magnetic_energy",
                                     "thermal_energy", "psi_energy", "total_energy", "momentum_x", "momentum_y",
                                     "cleaning_speed"})
      EXPECT_EQ(csv_column(a, column), csv_column(b, column)) << column;
    const Real extra = stepper == "leapfrog-blocks" ? 0 : 1;
    EXPECT_EQ(csv_column(b, "rhs_evals").back(), csv_column(a, "rhs_evals").back() + extra);
    std::printf("%s: stepper data of %zu numbers\n", stepper.c_str(), whole.stepper_data.size());
    EXPECT_FALSE(whole.stepper_data.empty());  // the levels / the partition
  }
}

TEST(PerParticleSteppers, WithoutATopStepTheyAreRefusedAtParse) {
  for (const std::string stepper : {"leapfrog-blocks", "mri-ARKODE_MIS_KW3"}) {
    expect_refused("water_drop", {"--stepper", stepper}, "--stepper: " + stepper + " needs its top step: give --max-dt");
    expect_refused("gravitating_sphere", {"--stepper", stepper}, "needs its top step");
  }
}

// Step options that contradict each other, refused before anything is written.
TEST(PerParticleSteppers, ContradictoryStepOptionsAreRefusedAtParse) {
  expect_refused("water_drop", {"--stepper", "leapfrog-blocks", "--dt", "1e-4", "--max-dt", "1e-5"},
                 "--max-dt: below --dt");
  expect_refused("water_drop", {"--dt", "1e-4", "--max-dt", "1e-5"}, "--max-dt: below --dt");  // any stepper
  expect_refused("water_drop", {"--stepper", "mri-ARKODE_MIS_KW3", "--mri-levels", "3", "--dt", "1e-5", "--mri-ratio", "1"},
                 "--mri-ratio: must be >= 2 with --mri-levels > 2 and --dt");
}

// The lattice's ghost scheme and the disc's fixed particles evaluate no particle subsets.
TEST(PerParticleSteppers, NotOfferedWhereTheSystemCannotEvaluateSubsets) {
  for (const std::string program : {"cylinder_lattice", "cleaning_disc"})
    for (const std::string stepper : {"leapfrog-blocks", "mri-ARKODE_MRI_GARK_ERK33a"})
      expect_refused(program, {"--stepper", stepper, "--max-dt", "0.01"}, "--stepper: bad value '" + stepper + "'");
}

// --max-dt 0.0005 [t_ff] caps the collapse's leapfrog at 0.0005 t_ff: 20 steps to 0.01 t_ff
// (read in code units it would be 0.0005 / t_ff's 8.89 and take 178); --dt likewise. run.json
// keeps the times as given, so `--config run.json` runs it again (it recorded them in code units,
// which a replay read as t_ff: 8.89x the end time and the step bound).
TEST(PerParticleSteppers, TheCollapseReadsAndRecordsItsStepOptionsInFreeFallTimes) {
  TempDir dir;
  const Args common = {"--particles", "1000", "--t-end", "0.01", "--output-every", "0.005", "--stepper", "leapfrog",
                       "--no-render", "--threads", "1"};
  const auto with = [&](Args more) {
    more.insert(more.begin(), common.begin(), common.end());
    return more;
  };
  const auto capped = dir.path() / "capped", fixed = dir.path() / "fixed";
  const Finished a = run(require_example("cloud_collapse"), with({"--max-dt", "0.0005", "--out", capped.string()}), dir.path());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_EQ(steps_of(capped / "cleaning_resistivity"), 20);
  const Finished b = run(require_example("cloud_collapse"), with({"--dt", "0.001", "--out", fixed.string()}), dir.path());
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(steps_of(fixed / "cleaning_resistivity"), 10);
  const auto again = dir.path() / "again";
  const Finished c = run(require_example("cloud_collapse"), {"--config", (capped / "run.json").string(), "--out", again.string()},
                         dir.path());
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(slurp(again / "cleaning_resistivity" / "diagnostics.csv"), slurp(capped / "cleaning_resistivity" / "diagnostics.csv"));
}
