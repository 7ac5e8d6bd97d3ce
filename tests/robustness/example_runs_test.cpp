// The water drop example end to end, on a tiny drop (80 particles):
//  - a forced NaN in the RHS: retried with smaller steps, then a clean failure (exit 3) with the
//    last good state written as VTK + a loadable checkpoint, the reason, time and particle named;
//  - checkpoint/restart: run to t1, restart to t2 == uninterrupted run to t2 (fixed-step
//    leapfrog: bit for bit, state and every output file; adaptive ERK: within the tolerance);
//  - SIGINT mid-run: exit 128+2 with a loadable checkpoint, whose restart again matches the
//    uninterrupted run bit for bit.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <thread>

#include "interrupt_run.hpp"
#include "run_example.hpp"
#include "sphark/io/vtp_reader.hpp"
#include "sphark/run/checkpoint.hpp"
#include "../support/bit_equal.hpp"
#include "../support/temp_dir.hpp"

using namespace sphark;
using namespace sphark::test;
namespace fs = std::filesystem;

namespace {
const std::vector<std::string> kTiny = {"--spacing", "0.2", "--scheme", "delta-sph", "--cleaning", "on", "--no-render",
                                        "--threads", "1"};
const std::vector<std::string> kLeapfrog = {"--stepper", "leapfrog", "--dt", "1e-5"};

std::vector<std::string> operator+(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

}  // namespace

TEST(ExampleRuns, ForcedNanIsRetriedThenFailsCleanlyWithTheLastGoodState) {
  const fs::path bin = require_example("water_drop");
  TempDir dir;
  const fs::path out = dir.path() / "nan";
  const Finished f = run(bin, kTiny + std::vector<std::string>{"--out", out.string(), "--t-end", "0.002",
                                                                "--output-every", "0.001", "--inject-nan-at", "0.0015"},
                         dir.path());
  EXPECT_EQ(f.exit_code, 3) << f.err;
  EXPECT_NE(f.err.find("cleaned run FAILED at t="), std::string::npos) << f.err;
  EXPECT_NE(f.err.find("velocity of particle 0"), std::string::npos) << f.err;   // which particles
  EXPECT_NE(f.err.find("min_dt"), std::string::npos) << f.err;                   // why ARKODE gave up
  const Checkpoint c = load_checkpoint(out / "cleaned" / "checkpoint.bin");
  EXPECT_LT(c.t, 0.0015);
  EXPECT_GT(c.t, 0.0014);  // the last good state: the last output before the fault, or later
  EXPECT_GT(c.scalar("rhs_recoveries"), 0);  // retried with smaller steps first
  for (Real v : c.y) ASSERT_TRUE(std::isfinite(v));
  // the last frame is that state, complete and readable
  const VtpContents frame = read_vtp(out / "cleaned" / "drop_00002.vtp");
  ASSERT_TRUE(frame.time.has_value());
  EXPECT_EQ(*frame.time, c.t);
  EXPECT_EQ(frame.count, c.particles());
  // every file complete: no temporaries left
  for (const auto& e : fs::directory_iterator(out / "cleaned"))
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();
}

TEST(ExampleRuns, RestartMatchesTheUninterruptedRun) {
  const fs::path bin = require_example("water_drop");
  TempDir dir;
  for (const bool leapfrog : {true, false}) {
    SCOPED_TRACE(leapfrog ? "leapfrog dt 1e-5" : "ERK Bogacki-Shampine rtol 1e-4");
    const auto opts = kTiny + (leapfrog ? kLeapfrog : std::vector<std::string>{}) +
                      std::vector<std::string>{"--output-every", "0.001", "--checkpoint-every", "0.001"};
    const std::string tag = leapfrog ? "lf" : "erk";
    const fs::path whole = dir.path() / (tag + "_whole"), first = dir.path() / (tag + "_first"),
                   second = dir.path() / (tag + "_second");
    ASSERT_EQ(run(bin, opts + std::vector<std::string>{"--out", whole.string(), "--t-end", "0.002"}, dir.path()).exit_code, 0);
    ASSERT_EQ(run(bin, opts + std::vector<std::string>{"--out", first.string(), "--t-end", "0.001"}, dir.path()).exit_code, 0);
    const Finished r = run(bin, {"--restart", (first / "cleaned" / "checkpoint.bin").string(), "--out", second.string(),
                                 "--t-end", "0.002"},
                           dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Checkpoint a = load_checkpoint(whole / "cleaned" / "checkpoint.bin");
    const Checkpoint b = load_checkpoint(second / "cleaned" / "checkpoint.bin");
    EXPECT_EQ(a.t, b.t);
    if (leapfrog) {
      EXPECT_TRUE(bit_equal(a.y, b.y));
      EXPECT_EQ(slurp(whole / "cleaned" / "diagnostics.csv"), slurp(second / "cleaned" / "diagnostics.csv"));
      EXPECT_EQ(slurp(whole / "cleaned" / "drop_00002.vtp"), slurp(second / "cleaned" / "drop_00002.vtp"));
      // the restart's series (another --out) lists every frame, the earlier ones in the first
      // run's folder, each byte-identical to the uninterrupted run's
      const std::vector<std::string> frames_a = pvd_files(whole / "cleaned" / "drop.pvd"),
                                     frames_b = pvd_files(second / "cleaned" / "drop.pvd");
      ASSERT_EQ(frames_a.size(), frames_b.size());
      EXPECT_EQ(frames_b.front(), "../../lf_first/cleaned/drop_00000.vtp");
      for (std::size_t k = 0; k < frames_a.size(); ++k)
        EXPECT_EQ(slurp(whole / "cleaned" / frames_a[k]), slurp(second / "cleaned" / frames_b[k])) << frames_b[k];
    } else {
      // positions: within rtol (1e-4) of the drop radius; densities: within rtol of rho0
      const std::size_t n = a.particles();
      Real dx = 0, drho = 0;
      for (std::size_t k = 0; k < 2 * n; ++k) dx = std::max(dx, std::abs(a.y[k] - b.y[k]));
      for (std::size_t k = 4 * n; k < 5 * n; ++k) drho = std::max(drho, std::abs(a.y[k] - b.y[k]));
      std::printf("ERK restart vs uninterrupted: max |dx| %.3g (R = 1), max |drho| %.3g (rho0 = 1000)\n", dx, drho);
      EXPECT_LT(dx, 1e-4 * 1.0);
      EXPECT_LT(drho, 1e-4 * 1000.0);
    }
  }
}

TEST(ExampleRuns, SigintLeavesALoadableCheckpointThatRestartsBitForBit) {
  const fs::path bin = require_example("water_drop");
  TempDir dir;
  const fs::path run1 = dir.path() / "interrupted";
  // long enough (t_end 1: 1e5 leapfrog steps) that SIGINT surely comes mid-run
  const Spawned s = spawn(bin, kTiny + kLeapfrog + std::vector<std::string>{"--out", run1.string(), "--t-end", "1",
                                                                             "--output-every", "0.01"},
                          dir.path());
  const Checkpoint c = interrupt_and_check(s, run1 / "cleaned" / "drop_00000.vtp", "stopped by signal 2",
                                           run1 / "cleaned", 1, std::chrono::milliseconds(200));
  ASSERT_GT(c.t, 0);  // the comparison below needs a mid-run checkpoint
  ASSERT_LT(c.t, 1);
  // continue a little past the checkpoint; an uninterrupted run to the same time agrees bit for bit
  char t_end[64];
  std::snprintf(t_end, sizeof t_end, "%.17g", (std::round(c.t / 1e-4) + 3) * 1e-4);
  std::printf("interrupted at t = %.6g; comparing at t = %s\n", c.t, t_end);
  const fs::path run2 = dir.path() / "restarted", whole = dir.path() / "whole";
  const Finished r = run(bin, {"--restart", (run1 / "cleaned" / "checkpoint.bin").string(), "--out", run2.string(),
                               "--t-end", t_end, "--output-every", t_end, "--checkpoint-every", t_end},
                         dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Finished w = run(bin, kTiny + kLeapfrog + std::vector<std::string>{"--out", whole.string(), "--t-end", t_end,
                                                                          "--output-every", t_end, "--checkpoint-every", t_end},
                         dir.path());
  ASSERT_EQ(w.exit_code, 0) << w.err;
  const Checkpoint a = load_checkpoint(run2 / "cleaned" / "checkpoint.bin");
  const Checkpoint b = load_checkpoint(whole / "cleaned" / "checkpoint.bin");
  EXPECT_EQ(a.t, b.t);
  EXPECT_TRUE(bit_equal(a.y, b.y));
}
