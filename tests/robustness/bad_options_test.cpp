// Every class of bad option on the examples: exit code 2, ONE line on stderr naming the option
// (and the value), and nothing written (the output directory is not even created).
#include <gtest/gtest.h>

#include "run_example.hpp"
#include "sphark/run/checkpoint.hpp"
#include "../support/temp_dir.hpp"

using namespace sphark;
using namespace sphark::test;

namespace {
struct BadInput {
  std::vector<std::string> args;
  std::string expect;  // substring of the one error line
};

std::string joined(const std::vector<std::string>& args) {
  std::string s;
  for (const auto& a : args) (s += a) += ' ';
  return s;
}

void expect_rejected(const std::filesystem::path& bin, const BadInput& b, const TempDir& dir,
                     const std::filesystem::path& out) {
  SCOPED_TRACE(joined(b.args));
  std::vector<std::string> args = b.args;
  if (std::find(args.begin(), args.end(), "--out") == args.end()) args.insert(args.begin(), {"--out", out.string()});
  const Finished f = run(bin, args, dir.path());
  EXPECT_EQ(f.exit_code, 2);
  EXPECT_NE(f.err.find(b.expect), std::string::npos) << f.err;
  EXPECT_EQ(std::count(f.err.begin(), f.err.end(), '\n'), 1) << f.err;
  EXPECT_TRUE(f.out.empty()) << f.out;
  EXPECT_FALSE(std::filesystem::exists(out));
  std::printf("[exit %d] %-60s -> %s", f.exit_code, joined(b.args).c_str(), f.err.c_str());
}
}  // namespace

TEST(BadOptions, WaterDropRejectsEveryClassWithOneLineAndNoFiles) {
  const auto bin = require_example("water_drop");
  TempDir dir;
  const auto out = dir.path() / "out";
  std::ofstream(dir.path() / "a_file") << "x";
  std::ofstream(dir.path() / "garbage.bin") << "not a checkpoint";
  const std::vector<BadInput> cases = {
      {{"--stepper", "rk99"}, "--stepper: bad value 'rk99'"},                // unknown name
      {{"--kernel", "gauss"}, "--kernel: bad value 'gauss'"},                // unknown variant
      {{"--cleaning", "maybe"}, "--cleaning: bad value 'maybe'"},
      {{"--scheme", "sph"}, "--scheme: bad value 'sph'"},
      {{"--delta", "0"}, "--delta: bad value '0'"},  // no diffusion is --scheme seed
      {{"--scheme", "seed", "--delta", "0.1"}, "--delta: --scheme seed has no density diffusion"},
      {{"--step-cap", "sometimes"}, "--step-cap: bad value 'sometimes'"},
      {{"--max-dt", "1e-300"}, "--max-dt: 1e-300 does not advance t"},
      {{"--max-dt", "1e-12"}, "--max-dt: 1e-12 is below the step floor"},
      {{"--initial-pressure", "hydrostatic"}, "--initial-pressure: bad value 'hydrostatic'"},
      {{"--frobnicate", "1"}, "--frobnicate"},                               // unknown option
      {{"--spacing", "0"}, "--spacing: bad value '0'"},                      // non-positive size
      {{"--spacing", "-0.1"}, "--spacing: bad value '-0.1'"},
      {{"--radius", "-1"}, "--radius: bad value '-1'"},
      {{"--spacing", "0.9"}, "--spacing: must be at most half the radius"},  // too few particles
      {{"--t-end", "0"}, "--t-end: bad value '0'"},                          // non-positive time
      {{"--t-end", "-1"}, "--t-end: bad value '-1'"},
      {{"--dt", "-1e-5"}, "--dt: bad value '-1e-5'"},
      {{"--diagnostics-every", "0"}, "--diagnostics-every: bad value '0'"},
      {{"--checkpoint-every", "-1"}, "--checkpoint-every: bad value '-1'"},
      {{"--output-every", "1", "--t-end", "0.5"}, "--output-every: must not exceed --t-end"},
      {{"--rtol", "0"}, "--rtol: bad value '0'"},                            // non-positive tolerance
      {{"--atol", "-1e-6"}, "--atol: bad value '-1e-6'"},
      {{"--rtol", "nan"}, "--rtol: bad value 'nan'"},                        // NaN / inf
      {{"--t-end", "inf"}, "--t-end: bad value 'inf'"},
      {{"--sound-speed", "NaN"}, "--sound-speed: bad value 'NaN'"},
      {{"--h-factor", "1e400"}, "--h-factor: bad value '1e400'"},
      {{"--threads", "-2"}, "--threads: bad value '-2'"},
      {{"--threads", "2.5"}, "--threads: bad value '2.5'"},
      {{"--t-end", "abc"}, "--t-end: bad value 'abc'"},                      // not a number
      {{"--t-end"}, "--t-end"},                                              // missing value
      {{"--restart", (dir.path() / "absent.bin").string()}, "--restart: checkpoint"},  // bad checkpoint
      {{"--restart", (dir.path() / "garbage.bin").string()}, "not a sphark checkpoint"},
  };
  for (const auto& c : cases) expect_rejected(bin, c, dir, out);
  // output directory that cannot be created / written: nothing appears
  for (const auto& bad_out : {(dir.path() / "a_file" / "sub").string(), std::string("/proc/sphark_out")}) {
    const Finished f = run(bin, {"--out", bad_out, "--t-end", "0.001", "--output-every", "0.0005", "--spacing", "0.2"}, dir.path());
    EXPECT_EQ(f.exit_code, 2) << bad_out;
    EXPECT_NE(f.err.find("--out: cannot create"), std::string::npos) << f.err;
    EXPECT_EQ(std::count(f.err.begin(), f.err.end(), '\n'), 1) << f.err;
    std::printf("[exit %d] --out %s -> %s", f.exit_code, bad_out.c_str(), f.err.c_str());
  }
  EXPECT_EQ(dir.entries(), (std::set<std::string>{"a_file", "garbage.bin", "stdout.txt", "stderr.txt"}));
}

TEST(BadOptions, WaterDropRestartMustMatchTheCheckpoint) {
  const auto bin = require_example("water_drop");
  TempDir dir;
  const auto ok = run(bin, {"--out", (dir.path() / "first").string(), "--spacing", "0.2", "--t-end", "0.0004",
                            "--cleaning", "on", "--no-render", "--checkpoint-every", "0.0002",
                            "--output-every", "0.0002"},
                      dir.path());
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const std::string ckpt = (dir.path() / "first" / "cleaned" / "checkpoint.bin").string();
  const auto out = dir.path() / "second";
  const std::vector<BadInput> cases = {
      {{"--restart", ckpt, "--spacing", "0.25"}, "--restart: scene parameters cannot change on restart: checkpoint has spacing=0.2, this run spacing=0.25"},
      {{"--restart", ckpt, "--delta", "0.1"}, "checkpoint has delta=0.05"},
      {{"--restart", ckpt, "--t-end", "0.0003"}, "--t-end: 0.0003 is not after the checkpoint time 0.0004"},
      {{"--restart", ckpt, "--cleaning", "off"}, "--cleaning: off contradicts the checkpoint (a cleaned run)"},
      {{"--restart", ckpt, "--scheme", "seed"}, "--scheme: seed contradicts the checkpoint (a cleaned run)"},
      {{"--restart", ckpt, "--rtol", "-1"}, "--rtol: bad value '-1'"},
  };
  for (const auto& c : cases) expect_rejected(bin, c, dir, out);
}

// A scene key written only when it differs from its default (old checkpoints restart): a restart
// that sets it is named by key, not by the line that happens to stand in its place.
TEST(BadOptions, ARestartNamesTheSceneKeyTheCheckpointLacks) {
  const auto bin = require_example("gravitating_sphere");
  TempDir dir;
  const auto ok = run(bin, {"--out", (dir.path() / "first").string(), "--particles", "400", "--t-end", "0.01",
                            "--checkpoint-every", "0.01", "--output-every", "0", "--no-render", "--threads", "1"},
                      dir.path());
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const std::string ckpt = (dir.path() / "first" / "uniform" / "checkpoint.bin").string();
  const std::vector<BadInput> cases = {
      {{"--restart", ckpt, "--opening", "mass", "--theta", "0.5"},
       "--restart: scene parameters cannot change on restart: checkpoint has no opening, this run opening=mass"},
  };
  for (const auto& c : cases) expect_rejected(bin, c, dir, dir.path() / "second");
}

TEST(BadOptions, SecondDerivative1dRejectsWithOneLineAndNoFiles) {
  const auto bin = require_example("second_derivative_1d");
  TempDir dir;
  const auto out = dir.path() / "out";
  std::ofstream(dir.path() / "a_file") << "x";
  const std::vector<BadInput> cases = {
      {{"--levels", "0"}, "--levels: bad value '0'"},
      {{"--levels", "11"}, "--levels: bad value '11'"},
      {{"--seeds", "nan"}, "--seeds: bad value 'nan'"},
      {{"--seed", "-3"}, "--seed: bad value '-3'"},
      {{"--colour", "red"}, "--colour"},
      {{"--out", (dir.path() / "a_file" / "sub").string()}, "--out: cannot create"},
  };
  for (const auto& c : cases) expect_rejected(bin, c, dir, out);
}

TEST(BadOptions, GhostStaticRejectsWithOneLineAndNoFiles) {
  const auto bin = require_example("ghost_static");
  TempDir dir;
  const auto out = dir.path() / "out";
  std::ofstream(dir.path() / "a_file") << "x";
  const std::vector<BadInput> cases = {
      {{"--particles", "10"}, "--particles: bad value '10'"},
      {{"--particles", "0"}, "--particles: bad value '0'"},
      {{"--draws", "inf"}, "--draws: bad value 'inf'"},
      {{"--seed", "-1"}, "--seed: bad value '-1'"},
      {{"--only", "fig6"}, "--only: bad value 'fig6'"},
      {{"--relax-map", "spherical"}, "--relax-map: bad value 'spherical'"},
      {{"--out", (dir.path() / "a_file" / "sub").string()}, "--out: cannot create"},
  };
  for (const auto& c : cases) expect_rejected(bin, c, dir, out);
}

TEST(BadOptions, CleaningDiscRejectsEveryClassWithOneLineAndNoFiles) {
  const auto bin = require_example("cleaning_disc");
  TempDir dir;
  const auto out = dir.path() / "out";
  std::ofstream(dir.path() / "a_file") << "x";
  std::ofstream(dir.path() / "garbage.bin") << "not a checkpoint";
  const std::vector<BadInput> cases = {
      {{"--variant", "constrained"}, "--variant: bad value 'constrained'"},  // unknown variant
      {{"--stepper", "leapfrog"}, "--stepper: bad value 'leapfrog'"},       // unknown stepper here
      {{"--spacing", "0"}, "--spacing: bad value '0'"},                     // non-positive size
      {{"--spacing", "0.5"}, "--spacing: must be at most 0.25"},
      {{"--t-end", "-2"}, "--t-end: bad value '-2'"},                       // non-positive time
      {{"--output-every", "20"}, "--output-every: must not exceed --t-end"},
      {{"--checkpoint-every", "-1"}, "--checkpoint-every: bad value '-1'"},
      {{"--rtol", "0"}, "--rtol: bad value '0'"},                           // non-positive tolerance
      {{"--atol", "nan"}, "--atol: bad value 'nan'"},                       // NaN / inf
      {{"--sigma", "inf"}, "--sigma: bad value 'inf'"},
      {{"--dt", "-1"}, "--dt: bad value '-1'"},
      {{"--inject-nan-at", "-1"}, "--inject-nan-at: bad value '-1'"},
      {{"--restart", (dir.path() / "absent.bin").string()}, "--restart: checkpoint"},
      {{"--restart", (dir.path() / "garbage.bin").string()}, "not a sphark checkpoint"},
      {{"--out", (dir.path() / "a_file" / "sub").string()}, "--out: cannot create"},
  };
  for (const auto& c : cases) expect_rejected(bin, c, dir, out);
}

TEST(BadOptions, OrszagTangRejectsEveryClassWithOneLineAndNoFiles) {
  const auto bin = require_example("orszag_tang");
  TempDir dir;
  const auto out = dir.path() / "out";
  std::ofstream(dir.path() / "a_file") << "x";
  // a checkpoint of another program
  const auto disc = require_example("cleaning_disc");
  ASSERT_EQ(run(disc, {"--out", (dir.path() / "disc").string(), "--spacing", "0.25", "--t-end", "0.1",
                       "--output-every", "0.1", "--variant", "constrained_sigma0", "--checkpoint-every", "0.1",
                       "--no-render"},
                dir.path())
                .exit_code,
            0);
  const std::string foreign = (dir.path() / "disc" / "constrained_sigma0.checkpoint.bin").string();
  const std::vector<BadInput> cases = {
      {{"--variant", "hall"}, "--variant: bad value 'hall'"},               // unknown variant
      {{"--stepper", "euler"}, "--stepper: bad value 'euler'"},             // unknown stepper
      {{"--nx", "4"}, "--nx: bad value '4'"},                               // too few particles
      {{"--nx", "-8"}, "--nx: bad value '-8'"},
      {{"--t-end", "0"}, "--t-end: bad value '0'"},                         // non-positive time
      {{"--output-every", "-0.1"}, "--output-every: bad value '-0.1'"},
      {{"--checkpoint-every", "2"}, "--checkpoint-every: must not exceed --t-end"},
      {{"--rtol", "-1e-4"}, "--rtol: bad value '-1e-4'"},                   // non-positive tolerance
      {{"--alpha-b", "0"}, "--alpha-b: bad value '0'"},
      {{"--sigma", "NaN"}, "--sigma: bad value 'NaN'"},                     // NaN / inf
      {{"--t-end", "inf"}, "--t-end: bad value 'inf'"},
      {{"--restart"}, "--restart: missing value"},
      {{"--restart", foreign}, "was written by cleaning_disc, not orszag_tang"},
      {{"--out", "/proc/sphark_out"}, "--out: cannot create"},
  };
  for (const auto& c : cases) expect_rejected(bin, c, dir, out);
}

TEST(BadOptions, StepperStudyRejectsWithOneLineAndNoFiles) {
  const auto bin = require_example("stepper_study");
  TempDir dir;
  const auto out = dir.path() / "out";
  const std::vector<BadInput> cases = {
      {{"--scene", "cube"}, "--scene: bad value 'cube'"},                              // unknown scene
      {{"--methods", "RK99"}, "--methods: unknown method 'RK99'"},                     // unknown stepper
      {{"--methods", "KNOTH_WOLKE_3_3"}, "has no embedding"},
      {{"--rtols", "1e-3,0"}, "--rtols: bad value '1e-3,0'"},                          // non-positive tolerance
      {{"--rtols", "1e-3,nan"}, "--rtols: bad value '1e-3,nan'"},                      // NaN
      {{"--fixed-cfls", "-0.1"}, "--fixed-cfls: bad value '-0.1'"},
      {{"--t-end", "-1"}, "--t-end: bad value '-1'"},                                  // negative time
      {{"--spacing", "inf"}, "--spacing: bad value 'inf'"},                            // inf size
      {{"--max-rhs", "0"}, "--max-rhs: bad value '0'"},
      {{"--out", "/proc/sphark_out"}, "--out: cannot create"},
  };
  for (const auto& c : cases) expect_rejected(bin, c, dir, out);
}
