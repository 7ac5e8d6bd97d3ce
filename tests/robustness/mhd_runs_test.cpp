// cleaning_disc and orszag_tang end to end through the shared run driver (run/time_loop.hpp), on
// tiny scenes (orszag_tang --nx 8: 80 particles; cleaning_disc --spacing 0.25: 52 particles):
//  - a forced NaN in the RHS: retried with smaller steps, then exit 3 with the last good state
//    written (VTK frame + checkpoint) and the reason, time and particle named;
//  - checkpoint/restart of one variant: leapfrog / fixed step bit for bit where the RHS depends on
//    the state alone, adaptive steps within the tolerance;
//  - SIGINT mid-run: exit 130 with a loadable checkpoint naming the variant;
//  - a run killed (SIGKILL) at arbitrary moments leaves only complete files under their final
//    names (every .vtp parses, the .pvd lists only existing frames, every CSV row is whole).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <regex>
#include <thread>

#include "../support/bit_equal.hpp"
#include "../support/temp_dir.hpp"
#include "interrupt_run.hpp"
#include "run_example.hpp"
#include "split_run.hpp"
#include "sphark/io/vtp_reader.hpp"
#include "sphark/run/checkpoint.hpp"
#include "sphark/run/time_loop.hpp"

using namespace sphark;
using namespace sphark::test;
namespace fs = std::filesystem;

namespace {
using Args = std::vector<std::string>;
const Args kOrszagTang = {"--nx", "8", "--variant", "cleaning", "--no-render", "--threads", "1"};
const Args kDisc = {"--spacing", "0.25", "--variant", "constrained_damped", "--no-render", "--threads", "1"};

Args operator+(Args a, const Args& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

Real max_abs_difference(const std::vector<Real>& a, const std::vector<Real>& b, std::size_t from, std::size_t to) {
  Real d = 0;
  for (std::size_t k = from; k < to; ++k) d = std::max(d, std::abs(a[k] - b[k]));
  return d;
}

std::size_t field_offset(const Checkpoint& c, const std::string& name) {
  std::size_t off = 0;
  for (const auto& f : c.species.at(0).fields) {
    if (f.name == name) return off;
    off += c.particles() * static_cast<std::size_t>(f.components);
  }
  ADD_FAILURE() << "no field " << name;
  return 0;
}

// Every file under its final name in `dir` is complete; returns the number of frames checked.
int expect_complete_files(const fs::path& dir) {
  int frames = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.find(".tmp.") != std::string::npos) continue;  // a temporary the kill interrupted
    SCOPED_TRACE(e.path().string());
    if (e.path().extension() == ".vtp") {
      EXPECT_NO_THROW(read_vtp(e.path()));
      ++frames;
    } else if (e.path().extension() == ".pvd") {
      EXPECT_NE(slurp(e.path()).find("</VTKFile>"), std::string::npos);
      for (const std::string& f : pvd_files(e.path())) EXPECT_TRUE(fs::exists(dir / f)) << f;
    } else if (e.path().extension() == ".csv") {
      const std::string text = slurp(e.path());
      EXPECT_FALSE(text.empty());
      if (text.empty()) continue;
      EXPECT_EQ(text.back(), '\n');
      const auto columns = std::count(text.begin(), text.begin() + text.find('\n'), ',');
      std::istringstream in(text);
      for (std::string line; std::getline(in, line);) EXPECT_EQ(std::count(line.begin(), line.end(), ','), columns) << line;
    } else if (e.path().extension() == ".bin") {
      EXPECT_NO_THROW(load_checkpoint(e.path()));
    }
  }
  return frames;
}
}  // namespace

TEST(MhdRuns, ForcedNanIsRetriedThenFailsCleanlyWithTheLastGoodState) {
  TempDir dir;
  struct Case {
    std::string program;
    Args args;
    fs::path run_dir, checkpoint, last_frame;
    std::string particle, why;
  };
  const fs::path ot = dir.path() / "ot", disc = dir.path() / "disc";
  const std::vector<Case> cases = {
      {"orszag_tang", kOrszagTang + Args{"--out", ot.string(), "--t-end", "0.2", "--output-every", "0.05"}, ot / "cleaning",
       ot / "cleaning" / "checkpoint.bin", ot / "cleaning" / "orszag_tang_00002.vtp", "velocity of particle 0",
       "recoverable RHS failure persists after 10 halvings"},
      {"cleaning_disc", kDisc + Args{"--out", disc.string(), "--t-end", "0.2", "--output-every", "0.05", "--variant",
                                     "constrained_sigma0"},
       disc, disc / "constrained_sigma0.checkpoint.bin", disc / "constrained_sigma0_00001.vtp", "magnetic_field of particle 0", "min_dt"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.program);
    const Finished f = run(require_example(c.program), c.args + Args{"--inject-nan-at", "0.07"}, dir.path());
    EXPECT_EQ(f.exit_code, 3) << f.err;
    EXPECT_NE(f.err.find("run FAILED at t="), std::string::npos) << f.err;
    EXPECT_NE(f.err.find(c.particle), std::string::npos) << f.err;  // which particles
    EXPECT_NE(f.err.find(c.why), std::string::npos) << f.err;       // why the stepper gave up
    EXPECT_NE(f.err.find("non-finite time derivative"), std::string::npos) << f.err;
    EXPECT_NE(f.err.find("last good state: " + c.last_frame.string()), std::string::npos) << f.err;
    const Checkpoint k = load_checkpoint(c.checkpoint);
    EXPECT_LT(k.t, 0.07);
    EXPECT_GE(k.t, 0.05);  // the last good state: the last output before the fault, or later
    EXPECT_GT(k.scalar("rhs_recoveries"), 0);  // retried with smaller steps first
    for (Real v : k.y) ASSERT_TRUE(std::isfinite(v));
    const VtpContents frame = read_vtp(c.last_frame);
    ASSERT_TRUE(frame.time.has_value());
    EXPECT_EQ(*frame.time, k.t);
    EXPECT_EQ(frame.count, k.particles());
    for (const auto& e : fs::directory_iterator(c.run_dir))
      EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();
  }
}

TEST(MhdRuns, OrszagTangRestartMatchesTheUninterruptedRun) {
  TempDir dir;
  for (const bool leapfrog : {true, false}) {
    SCOPED_TRACE(leapfrog ? "leapfrog" : "ERK Bogacki-Shampine rtol 1e-6");
    const Args opts = kOrszagTang + (leapfrog ? Args{} : Args{"--stepper", "ARKODE_BOGACKI_SHAMPINE_4_2_3", "--rtol", "1e-6"}) +
                      Args{"--output-every", "0.05", "--checkpoint-every", "0.1"} +
                      Args{"--resort", "0.02"};  // re-sorts on the way (run/state_resort.hpp), restarts included
    const std::string tag = leapfrog ? "lf" : "erk";
    Checkpoint a, b;
    ASSERT_TRUE(split_run("orszag_tang", opts, dir.path(), tag, "cleaning/checkpoint.bin", a, b));
    EXPECT_EQ(b.text("run"), "cleaning");
    EXPECT_EQ(a.t, b.t);
    EXPECT_EQ(csv_column(a.text("diagnostics.csv"), "t"), csv_column(b.text("diagnostics.csv"), "t"));
    const std::size_t x = field_offset(a, "position"), v = field_offset(a, "velocity");
    const Real dx = max_abs_difference(a.y, b.y, x, x + 2 * a.particles());
    const Real dv = max_abs_difference(a.y, b.y, v, v + 2 * a.particles());
    std::printf("orszag_tang %s restart vs uninterrupted at t=%g: max |dx| %.3g, max |dv| %.3g (box 1, |v| ~ 1), "
                "bit-identical: %s\n", tag.c_str(), a.t, dx, dv, bit_equal(a.y, b.y) ? "yes" : "no");
    if (leapfrog) {
      // Bit for bit: the checkpoint carries the h the solve starts from (OdeSystem::resume_data)
      // and the scheme's sums do not depend on when its lists were built.
      EXPECT_TRUE(bit_equal(a.y, b.y));
    } else {
      EXPECT_LT(dx, 1e-6 * 1.0 * 10);
      EXPECT_LT(dv, 1e-6 * 1.0 * 10);
    }
  }
}

TEST(MhdRuns, CleaningDiscRestartMatchesTheUninterruptedRun) {
  TempDir dir;
  for (const bool fixed : {true, false}) {
    SCOPED_TRACE(fixed ? "DOPRI5 fixed dt 1e-3" : "DOPRI5 adaptive rtol 1e-7");
    const Args opts = kDisc + Args{"--stepper", "ARKODE_DORMAND_PRINCE_7_4_5"} +
                      (fixed ? Args{"--dt", "1e-3"} : Args{"--rtol", "1e-7", "--step-cap", "on"}) +
                      Args{"--output-every", "0.05", "--checkpoint-every", "0.1"};
    const std::string tag = fixed ? "fixed" : "adaptive";
    Checkpoint a, b;
    ASSERT_TRUE(split_run("cleaning_disc", opts, dir.path(), tag, "constrained_damped.checkpoint.bin", a, b));
    EXPECT_EQ(a.t, b.t);
    const Real d = max_abs_difference(a.y, b.y, 0, a.y.size());
    std::printf("cleaning_disc %s restart vs uninterrupted at t=%g: max |dB|, |dpsi| %.3g (B0 = 0.28)\n", tag.c_str(), a.t, d);
    if (fixed) {
      EXPECT_TRUE(bit_equal(a.y, b.y));
      EXPECT_EQ(slurp(dir.path() / "fixed_whole" / "constrained_damped.csv"),
                slurp(dir.path() / "fixed_second" / "constrained_damped.csv"));
    } else {
      EXPECT_LT(d, 1e-7 * 10);  // within rtol of |B| ~ 0.3 (the controller's history is not restored)
    }
  }
}

TEST(MhdRuns, SigintLeavesALoadableCheckpointNamingTheVariant) {
  TempDir dir;
  const fs::path out = dir.path() / "interrupted";
  // long enough (t_end 1000) that SIGINT surely comes mid-run
  const Spawned s = spawn(require_example("orszag_tang"), kOrszagTang + Args{"--out", out.string(), "--t-end", "1000",
                                                                    "--output-every", "0.5"},
                          dir.path());
  const Checkpoint c = interrupt_and_check(s, out / "cleaning" / "orszag_tang_00001.vtp",
                                           "cleaning run stopped by signal 2", out / "cleaning", 1000);
  EXPECT_EQ(c.text("run"), "cleaning");
  expect_complete_files(out / "cleaning");
  // --variant must agree with the checkpoint's
  const Finished wrong = run(require_example("orszag_tang"), {"--restart", (out / "cleaning" / "checkpoint.bin").string(),
                                                     "--variant", "euler", "--out", (dir.path() / "x").string()},
                             dir.path());
  EXPECT_EQ(wrong.exit_code, 2);
  EXPECT_NE(wrong.err.find("--variant: euler contradicts the checkpoint (variant cleaning)"), std::string::npos) << wrong.err;
  EXPECT_FALSE(fs::exists(dir.path() / "x"));
}

TEST(MhdRuns, AKilledRunLeavesOnlyCompleteFiles) {
  TempDir dir;
  // frames and checkpoints as often as possible, killed (SIGKILL: no handler runs) at several moments
  int frames = 0;
  for (const int delay_ms : {0, 150, 400}) {  // after the first checkpoint
    SCOPED_TRACE(delay_ms);
    const fs::path out = dir.path() / ("killed_" + std::to_string(delay_ms));
    const Spawned s = spawn(require_example("orszag_tang"), kOrszagTang + Args{"--out", out.string(), "--t-end", "1000",
                                                                      "--output-every", "0.02", "--checkpoint-every",
                                                                      "0.02"},
                            dir.path());
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!fs::exists(out / "cleaning" / "checkpoint.bin") && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
    kill(s.pid, SIGKILL);
    wait_for(s);
    frames += expect_complete_files(out / "cleaning");
    EXPECT_NO_THROW(load_checkpoint(out / "cleaning" / "checkpoint.bin"));
  }
  EXPECT_GE(frames, 6);  // at least the frames before each first checkpoint (t = 0, 0.02)
}

TEST(MhdRuns, RestartOnAnotherOutputGridContinuesFromTheCheckpoint) {
  TempDir dir;
  const fs::path first = dir.path() / "first", second = dir.path() / "second";
  ASSERT_EQ(run(require_example("orszag_tang"), kOrszagTang + Args{"--out", first.string(), "--t-end", "0.1", "--output-every",
                                                          "0.05", "--checkpoint-every", "0.1"},
                dir.path())
                .exit_code,
            0);
  const Finished r = run(require_example("orszag_tang"), {"--restart", (first / "cleaning" / "checkpoint.bin").string(), "--out",
                                                 second.string(), "--t-end", "0.2", "--output-every", "0.03"},
                         dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Checkpoint c = load_checkpoint(second / "cleaning" / "checkpoint.bin");
  const std::vector<Real> t = csv_column(slurp(second / "cleaning" / "diagnostics.csv"), "t");
  // the first run's rows (0, 0.05, 0.1), then the new grid from the checkpoint on: 0.12, 0.15, 0.18, and t_end
  const std::vector<Real> expected = {0, 0.05, 0.1, 0.12, 0.15, 0.18, 0.2};
  ASSERT_EQ(t.size(), expected.size());
  for (std::size_t k = 0; k < t.size(); ++k) EXPECT_NEAR(t[k], expected[k], 1e-12);
  EXPECT_EQ(c.t, t.back());
  EXPECT_EQ(csv_column(c.text("diagnostics.csv"), "t"), t);
}
