// cylinder_lattice (seed 004 §8) end to end through the shared run driver, on a tiny single run
// (100 particles, leapfrog):
//  - bad options: exit 2, one line naming the option and value, nothing written;
//  - checkpoint/restart round trip against the uninterrupted run;
//  - SIGINT mid-run: exit 130 with a loadable checkpoint naming the map;
//  - a forced NaN: exit 3 with the last good state (VTK frame + checkpoint) and the reason;
//  - SIGINT during the ensemble: exit 130, ensemble.csv holds exactly the runs done, every row whole.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "../support/temp_dir.hpp"
#include "interrupt_run.hpp"
#include "run_example.hpp"
#include "sphark/run/checkpoint.hpp"
#include "sphark/run/time_loop.hpp"

using namespace sphark;
using namespace sphark::test;
namespace fs = std::filesystem;

namespace {
using Args = std::vector<std::string>;
const Args kSingle = {"--case", "single", "--particles", "100", "--threads", "1", "--no-render"};

Args operator+(Args a, const Args& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

int lines(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }
}  // namespace

TEST(LatticeRuns, BadOptionsExitTwoWithOneLineAndWriteNothing) {
  TempDir dir;
  const fs::path good = dir.path() / "good";
  ASSERT_EQ(run(require_example("cylinder_lattice"), kSingle + Args{"--out", good.string(), "--t-end", "0.1", "--checkpoint-every", "0.1"},
                dir.path())
                .exit_code,
            0);
  const std::string ckpt = (good / "single_nonlinear" / "checkpoint.bin").string();
  const fs::path garbage = dir.path() / "garbage.bin";
  { std::ofstream(garbage) << "not a checkpoint"; }
  const std::vector<std::pair<Args, std::string>> cases = {
      {{"--case", "ensemble", "--checkpoint-every", "1"}, "--checkpoint-every: not available with --case ensemble"},
      {{"--case", "ensemble", "--inject-nan-at", "1"}, "--inject-nan-at: not available with --case ensemble"},
      {{"--checkpoint-every", "20"}, "--checkpoint-every: must not exceed --t-end"},
      {{"--checkpoint-every", "-1"}, "--checkpoint-every: bad value '-1'"},
      {{"--inject-nan-at", "-1"}, "--inject-nan-at: bad value '-1'"},
      {{"--output-every", "20"}, "--output-every: must not exceed --t-end"},
      {{"--restart", (dir.path() / "none.bin").string()}, "--restart: checkpoint"},
      {{"--restart", garbage.string()}, "--restart"},
      {{"--restart", ckpt, "--v0", "0.3"},
       "--restart: scene parameters cannot change on restart: checkpoint has v0=0.5, this run v0=0.3"},
      {{"--restart", ckpt, "--seed", "7"}, "checkpoint has seed=1, this run seed=7"},
      {{"--restart", ckpt, "--case", "medium"}, "checkpoint has case=single, this run case=medium"},
      {{"--restart", ckpt, "--map", "mirror"}, "--map: mirror contradicts the checkpoint (map nonlinear)"},
      {{"--restart", ckpt, "--t-end", "0.05"}, "--t-end"},
      {{"--case", "single", "--map", "both"}, "--map: 'both' is not allowed with --case single"},
  };
  for (const auto& [args, message] : cases) {
    const fs::path out = dir.path() / "bad";
    Args all = Args{"--t-end", "10", "--out", out.string()} + args;
    const Finished f = run(require_example("cylinder_lattice"), all, dir.path());
    SCOPED_TRACE(args.front() + " " + args.back());
    EXPECT_EQ(f.exit_code, 2) << f.err;
    EXPECT_EQ(lines(f.err), 1) << f.err;
    EXPECT_EQ(f.err.rfind("cylinder_lattice: ", 0), 0u) << f.err;
    EXPECT_NE(f.err.find(message), std::string::npos) << f.err;
    EXPECT_FALSE(fs::exists(out));
  }
}

TEST(LatticeRuns, LeapfrogRestartMatchesTheUninterruptedRun) {
  TempDir dir;
  const fs::path whole = dir.path() / "whole", first = dir.path() / "first", second = dir.path() / "second";
  const Args opts = kSingle + Args{"--output-every", "0.1", "--checkpoint-every", "0.1"};
  ASSERT_EQ(run(require_example("cylinder_lattice"), opts + Args{"--out", whole.string(), "--t-end", "0.4"}, dir.path()).exit_code, 0);
  ASSERT_EQ(run(require_example("cylinder_lattice"), opts + Args{"--out", first.string(), "--t-end", "0.2"}, dir.path()).exit_code, 0);
  const std::string ckpt = "single_nonlinear/checkpoint.bin";
  const Finished r = run(require_example("cylinder_lattice"), {"--restart", (first / ckpt).string(), "--out", second.string(), "--t-end", "0.4"},
                         dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Checkpoint a = load_checkpoint(whole / ckpt), b = load_checkpoint(second / ckpt);
  EXPECT_EQ(b.text("run"), "nonlinear");
  EXPECT_EQ(a.t, b.t);
  EXPECT_EQ(a.t, 0.4);
  EXPECT_EQ(a.text("scene"), b.text("scene"));
  EXPECT_EQ(csv_column(a.text("diagnostics.csv"), "t"), csv_column(b.text("diagnostics.csv"), "t"));
  EXPECT_EQ(csv_column(a.text("diagnostics.csv"), "steps"), csv_column(b.text("diagnostics.csv"), "steps"));
  ASSERT_EQ(a.y.size(), b.y.size());
  Real d = 0, scale = 0;
  for (std::size_t k = 0; k < a.y.size(); ++k) {
    d = std::max(d, std::abs(a.y[k] - b.y[k]));
    scale = std::max(scale, std::abs(a.y[k]));
  }
  std::printf("cylinder_lattice restart vs uninterrupted at t=%g: max |dy| %.3g (max |y| %.3g), bit-identical: %s\n", a.t,
              d, scale, a.y == b.y ? "yes" : "no");
  // Bit for bit: the h-rho solve starts Newton from the previous h, which the checkpoint carries
  // (OdeSystem::resume_data; before, the restart started from the uniform first guess and agreed
  // to 3.75e-15 only).
  EXPECT_TRUE(a.y == b.y);
  EXPECT_EQ(a.system_data, b.system_data);
  EXPECT_EQ(a.system_data.size(), a.particles());
}

TEST(LatticeRuns, SigintLeavesALoadableCheckpointNamingTheMap) {
  TempDir dir;
  const fs::path out = dir.path() / "interrupted";
  // weak driving (v0 0.05): no penetration or accumulation event; t_end 1000: SIGINT comes mid-run
  const Spawned s = spawn(require_example("cylinder_lattice"), kSingle + Args{"--out", out.string(), "--t-end", "1000", "--output-every",
                                                           "0.5", "--v0", "0.05"},
                          dir.path());
  const Checkpoint c = interrupt_and_check(s, out / "single_nonlinear" / "lattice_00001.vtp",
                                           "nonlinear run stopped by signal 2", out / "single_nonlinear", 1000);
  EXPECT_EQ(c.text("run"), "nonlinear");
  // and it continues
  const Finished r = run(require_example("cylinder_lattice"), {"--restart", (out / "single_nonlinear" / "checkpoint.bin").string(), "--t-end",
                                            std::to_string(c.t + 0.5)},
                         dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  // the restart (same --out) continues both series: one ghost frame per particle frame
  const auto frames = [&](const std::string& pvd) {
    const std::string xml = slurp(out / "single_nonlinear" / pvd);
    std::size_t n = 0;
    for (auto at = xml.find("file=\""); at != std::string::npos; at = xml.find("file=\"", at + 1)) ++n;
    return n;
  };
  EXPECT_GE(frames("lattice.pvd"), 3u);
  EXPECT_EQ(frames("ghosts.pvd"), frames("lattice.pvd"));
}

TEST(LatticeRuns, ForcedNanFailsWithTheLastGoodState) {
  TempDir dir;
  const fs::path out = dir.path() / "nan";
  const Finished f = run(require_example("cylinder_lattice"), kSingle + Args{"--out", out.string(), "--t-end", "0.4", "--output-every", "0.1",
                                                          "--inject-nan-at", "0.25"},
                         dir.path());
  EXPECT_EQ(f.exit_code, 3) << f.err;
  EXPECT_NE(f.err.find("nonlinear run FAILED at t="), std::string::npos) << f.err;
  EXPECT_NE(f.err.find("last good state"), std::string::npos) << f.err;
  const Checkpoint c = load_checkpoint(out / "single_nonlinear" / "checkpoint.bin");
  EXPECT_GE(c.t, 0.2);
  EXPECT_LT(c.t, 0.25 + 1e-12);
  for (Real v : c.y) ASSERT_TRUE(std::isfinite(v));
  EXPECT_TRUE(fs::exists(out / "single_nonlinear" / "lattice_00003.vtp"));  // 0, 0.1, 0.2, last good
}

TEST(LatticeRuns, SigintDuringTheEnsembleKeepsTheRunsDone) {
  TempDir dir;
  const fs::path out = dir.path() / "ensemble";
  const Spawned s = spawn(require_example("cylinder_lattice"), {"--case", "ensemble", "--particles", "100", "--t-end", "0.5", "--seeds",
                                             "1000", "--v0-list", "0.1", "--map", "nonlinear", "--threads", "1",
                                             "--no-render", "--out", out.string()},
                          dir.path());
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (slurp(s.err).find("20/1000 runs") == std::string::npos && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  kill(s.pid, SIGINT);
  const Finished f = wait_for(s);
  EXPECT_EQ(f.exit_code, 128 + SIGINT) << f.err;
  EXPECT_NE(f.err.find("ensemble stopped by signal 2 after"), std::string::npos) << f.err;
  const std::string csv = slurp(out / "ensemble.csv");
  ASSERT_FALSE(csv.empty());
  EXPECT_EQ(csv.back(), '\n');
  const int rows = lines(csv) - 1;
  EXPECT_GE(rows, 20);
  EXPECT_LT(rows, 1000);
  EXPECT_NE(f.err.find("after " + std::to_string(rows) + " of 1000 runs"), std::string::npos) << f.err;
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line);) EXPECT_EQ(std::count(line.begin(), line.end(), ','), 4) << line;
}

TEST(LatticeRuns, AnEventEndsTheDrivenRunAtItsRootWithAFrame) {
  // the mirror map's ghosts pile up at once (docs/cylinder_lattice.md): accumulation event, exit 0
  TempDir dir;
  const fs::path out = dir.path() / "event";
  const Finished f = run(require_example("cylinder_lattice"), kSingle + Args{"--map", "mirror", "--out", out.string(), "--t-end", "2",
                                                          "--output-every", "0.5"},
                         dir.path());
  EXPECT_EQ(f.exit_code, 0) << f.err;
  const std::string csv = slurp(out / "single_mirror" / "diagnostics.csv");
  const std::vector<Real> t = csv_column(csv, "t"), h = csv_column(csv, "min_ghost_h_over_h_ref");
  ASSERT_EQ(t.size(), 2u);  // t = 0 and the root time, before the first grid time 0.5
  EXPECT_GT(t[1], 0);
  EXPECT_LT(t[1], 0.5);
  EXPECT_GT(h[0], 0.05);  // above the threshold (0.05, --accumulation default) at t = 0 ...
  EXPECT_LT(h[1], 0.05);  // ... below it where the stepper located the crossing (measured 0.041)
  EXPECT_NE(slurp(out / "single_mirror" / "summary.csv").find("\"accumulation\""), std::string::npos);
  EXPECT_TRUE(fs::exists(out / "single_mirror" / "lattice_00001.vtp"));
  EXPECT_TRUE(fs::exists(out / "single_mirror" / "fields_end.csv"));
}

// --cfl 0 (the default) is the case's CFL number: 0.25 for single (kept in the checkpoint's scene
// text), 0.4 for the ensemble (its runs take the steps of --cfl 0.4, not those of 0.25).
TEST(LatticeRuns, TheDefaultCflIsTheCases) {
  TempDir dir;
  const fs::path single = dir.path() / "single";
  ASSERT_EQ(run(require_example("cylinder_lattice"),
                kSingle + Args{"--out", single.string(), "--t-end", "0.1", "--checkpoint-every", "0.1"}, dir.path())
                .exit_code,
            0);
  EXPECT_NE(load_checkpoint(single / "single_nonlinear" / "checkpoint.bin").text("scene").find("\ncfl=0.25\n"),
            std::string::npos);
  const auto ensemble_steps = [&](const Args& cfl) {
    const fs::path out = dir.path() / ("ensemble" + std::to_string(cfl.size()) + (cfl.empty() ? "" : cfl[1]));
    const Finished f = run(require_example("cylinder_lattice"),
                           Args{"--case", "ensemble", "--particles", "100", "--t-end", "0.2", "--seeds", "1", "--v0-list",
                                "0.5", "--map", "nonlinear", "--threads", "1", "--no-render", "--out", out.string()} +
                               cfl,
                           dir.path());
    EXPECT_EQ(f.exit_code, 0) << f.err;
    return csv_column(slurp(out / "ensemble_runs.csv"), "steps");
  };
  const std::vector<Real> by_default = ensemble_steps({}), at_04 = ensemble_steps({"--cfl", "0.4"}),
                          at_025 = ensemble_steps({"--cfl", "0.25"});
  ASSERT_EQ(by_default.size(), 1u);
  EXPECT_EQ(by_default, at_04);
  EXPECT_GT(at_025[0], 1.5 * at_04[0]);  // measured 40 against 25 steps (0.4 / 0.25 = 1.6)
}
