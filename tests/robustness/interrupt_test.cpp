// SIGINT / SIGTERM end every kind of run within a second (issue #21): during the set-up (a long
// relaxation with its own poll; a large particle set without one: the set-up watchdog), in the
// middle of a long output interval (the steppers poll before every RHS evaluation: the
// checkpoint holds the last accepted step, and a leapfrog restart from it continues bit for
// bit), in the lattice ensemble and in the stepper study.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>

#include "run_example.hpp"
#include "sphark/io/run_record.hpp"
#include "sphark/run/checkpoint.hpp"
#include "../support/bit_equal.hpp"
#include "../support/temp_dir.hpp"

using namespace sphark;
using namespace sphark::test;
namespace fs = std::filesystem;

namespace {

constexpr double kWithin = 1.0;  // seconds from the signal to the exit

std::vector<std::string> operator+(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string outcome(const fs::path& run_json) {
  const Json record = read_run_record(run_json);  // find() points into it: keep it alive
  const Json* o = record.find("outcome");
  return o ? o->as_string() : "(none)";
}

// A stop during the set-up: 128 + sig within a second, run.json "stopped", no checkpoint.
void expect_setup_stop(const std::string& program, const std::vector<std::string>& args, int sig) {
  SCOPED_TRACE(program);
  TempDir dir;
  const fs::path out = dir.path() / "out";
  const Spawned s = spawn(require_example(program), args + std::vector<std::string>{"--out", out.string()}, dir.path());
  const Timed r = signal_when(s, out / "run.json", sig, std::chrono::milliseconds(500));
  std::printf("%s: signal %d during the set-up answered in %.3f s: %s", program.c_str(), sig, r.after_stop,
              r.f.err.c_str());
  EXPECT_EQ(r.f.exit_code, 128 + sig) << r.f.err;
  EXPECT_LT(r.after_stop, kWithin);
  EXPECT_TRUE(contains(r.f.err, "during the set-up")) << r.f.err;
  EXPECT_EQ(outcome(out / "run.json"), "stopped");
  for (const auto& e : fs::recursive_directory_iterator(out))
    EXPECT_EQ(e.path().filename().string().find("checkpoint"), std::string::npos) << e.path();
}

}  // namespace

// The relaxation of 50000 particles polls every iteration.
TEST(Interrupt, DuringTheRelaxationOfTheLatticeSetUp) {
  expect_setup_stop("cylinder_lattice", {"--particles", "50000", "--t-end", "1", "--no-render"}, SIGINT);
}

// 785000 particles: building them and their first neighbour lists has no poll; the watchdog.
TEST(Interrupt, DuringALargeSetUpWithoutAPoll) {
  expect_setup_stop("water_drop", {"--spacing", "0.002", "--cleaning", "on", "--t-end", "1e-4", "--no-render"}, SIGTERM);
}

// One diagnostics interval of 0.05 (thousands of steps): the stop comes mid-interval.
TEST(Interrupt, MidIntervalWithACheckpointThatRestartsBitForBit) {
  const fs::path bin = require_example("water_drop");
  TempDir dir;
  const std::vector<std::string> lf = {"--spacing", "0.1", "--cleaning", "on", "--no-render", "--stepper", "leapfrog",
                                       "--dt", "1e-5", "--diagnostics-every", "0.05", "--output-every", "0.05"};
  const fs::path run1 = dir.path() / "interrupted";
  const Spawned s = spawn(bin, lf + std::vector<std::string>{"--t-end", "0.1", "--out", run1.string()}, dir.path());
  const Timed r = signal_when(s, run1 / "cleaned" / "drop_00000.vtp", SIGINT, std::chrono::milliseconds(300));
  std::printf("SIGINT mid-interval answered in %.3f s\n", r.after_stop);
  EXPECT_EQ(r.f.exit_code, 128 + SIGINT) << r.f.err;
  EXPECT_LT(r.after_stop, kWithin);
  const Checkpoint c = load_checkpoint(run1 / "cleaned" / "checkpoint.bin");
  ASSERT_GT(c.t, 0);
  ASSERT_LT(c.t, 0.05);  // before the first grid time: a mid-interval state
  std::printf("checkpoint at t = %.9g (step %g)\n", c.t, c.scalar("steps"));
  // continue to the grid time 0.05; the uninterrupted run to 0.05 agrees bit for bit
  const fs::path run2 = dir.path() / "restarted", whole = dir.path() / "whole";
  const Finished a = run(bin, {"--restart", (run1 / "cleaned" / "checkpoint.bin").string(), "--out", run2.string(),
                               "--t-end", "0.05", "--checkpoint-every", "0.05"},
                         dir.path());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const Finished b = run(bin, lf + std::vector<std::string>{"--t-end", "0.05", "--checkpoint-every", "0.05", "--out",
                                                            whole.string()},
                         dir.path());
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const Checkpoint ca = load_checkpoint(run2 / "cleaned" / "checkpoint.bin");
  const Checkpoint cb = load_checkpoint(whole / "cleaned" / "checkpoint.bin");
  EXPECT_EQ(ca.t, cb.t);
  EXPECT_TRUE(bit_equal(ca.y, cb.y));
  EXPECT_EQ(slurp(run2 / "cleaned" / "diagnostics.csv"), slurp(whole / "cleaned" / "diagnostics.csv"));
}

// The adaptive ARKODE path: interrupted inside a step attempt, the last accepted step is kept.
TEST(Interrupt, MidIntervalOfAnAdaptiveRun) {
  const fs::path bin = require_example("water_drop");
  TempDir dir;
  const fs::path out = dir.path() / "erk";
  const Spawned s = spawn(bin,
                          {"--spacing", "0.1", "--scheme", "delta-sph", "--cleaning", "on", "--step-cap", "on",
                           "--no-render", "--diagnostics-every", "0.05",
                           "--output-every", "0.05", "--t-end", "0.1", "--out", out.string()},
                          dir.path());
  const Timed r = signal_when(s, out / "cleaned" / "drop_00000.vtp", SIGTERM, std::chrono::milliseconds(300));
  EXPECT_EQ(r.f.exit_code, 128 + SIGTERM) << r.f.err;
  EXPECT_LT(r.after_stop, kWithin);
  const Checkpoint c = load_checkpoint(out / "cleaned" / "checkpoint.bin");
  EXPECT_GT(c.t, 0);
  EXPECT_LT(c.t, 0.05);
  EXPECT_GT(c.last_dt, 0);
  for (Real v : c.y) ASSERT_TRUE(std::isfinite(v));
  const Finished more = run(bin, {"--restart", (out / "cleaned" / "checkpoint.bin").string(), "--out",
                                  (dir.path() / "more").string(), "--t-end", "0.05"},
                            dir.path());
  EXPECT_EQ(more.exit_code, 0) << more.err;
}

// The ensemble's runs in progress stop too (each takes ~15 s: before, they ran to their end);
// ensemble.csv holds the completed runs only.
TEST(Interrupt, InTheLatticeEnsemble) {
  TempDir dir;
  const fs::path out = dir.path() / "ens";
  const Spawned s = spawn(require_example("cylinder_lattice"),
                          {"--case", "ensemble", "--seeds", "4", "--particles", "1000", "--v0-list", "0.05", "--t-end",
                           "10", "--no-render", "--threads", "2", "--out", out.string()},  // runs of ~15 s each
                          dir.path());
  const Timed r = signal_when(s, out / "run.json", SIGTERM, std::chrono::milliseconds(1500));
  std::printf("ensemble: SIGTERM answered in %.3f s: %s", r.after_stop, r.f.err.c_str());
  EXPECT_EQ(r.f.exit_code, 128 + SIGTERM) << r.f.err;
  EXPECT_LT(r.after_stop, kWithin);
  const std::string csv = slurp(out / "ensemble.csv");
  EXPECT_EQ(csv.rfind("map,v0,seed,t_max,reason\n", 0), 0u) << csv;
  EXPECT_FALSE(contains(csv, "stopped")) << csv;
  EXPECT_EQ(outcome(out / "run.json"), "stopped");
}

// The study: the reference run (VERNER_8_5_6, rtol 1e-10) is long; no row for a cut-short case.
TEST(Interrupt, InTheStepperStudy) {
  TempDir dir;
  const fs::path out = dir.path() / "study";
  const Spawned s = spawn(require_example("stepper_study"),
                          {"--scene", "drop", "--what", "matrix", "--no-render", "--out", out.string()}, dir.path());
  const Timed r = signal_when(s, out / "work_precision.csv", SIGINT, std::chrono::milliseconds(500));
  std::printf("study: SIGINT answered in %.3f s\n", r.after_stop);
  EXPECT_EQ(r.f.exit_code, 128 + SIGINT) << r.f.err;
  EXPECT_LT(r.after_stop, kWithin);
  const std::string rows = slurp(out / "work_precision.csv");
  EXPECT_EQ(std::count(rows.begin(), rows.end(), '\n'), 1) << rows;  // the header: no case finished
  EXPECT_FALSE(fs::exists(out / "reference.csv"));
}
