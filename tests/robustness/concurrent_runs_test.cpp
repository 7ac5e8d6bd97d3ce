// Runs side by side (run/concurrent_jobs.hpp, --concurrent-runs): each job once, each lane on its
// own OpenMP thread count, a failure or a stop starts no new job, an exception reaches the caller;
// the water drop's four runs two at a time write what they write one after the other, byte for
// byte, and report in the order of the runs; SIGINT checkpoints both runs in progress.
#include <gtest/gtest.h>
#include <omp.h>

#include <atomic>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <chrono>

#include "interrupt_run.hpp"
#include "run_example.hpp"
#include "sphark/run/concurrent_jobs.hpp"
#include "sphark/run/signals.hpp"
#include "../support/file_bytes.hpp"
#include "../support/temp_dir.hpp"

using namespace sphark;
using namespace sphark::test;
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kFourRuns = {"--spacing", "0.2", "--scheme", "both", "--cleaning", "both",
                                            "--no-render"};
const std::vector<std::string> kRunsInOrder = {"seed_cleaned", "seed_control", "cleaned", "control"};

std::vector<std::string> operator+(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

}  // namespace

TEST(RunConcurrently, EveryJobOnceOnItsLanesThreadCount) {
  for (const int lanes : {1, 2, 3}) {
    std::mutex m;
    std::multiset<std::size_t> seen;
    std::atomic<int> wrong_threads{0};
    const std::size_t started = run_concurrently(7, lanes, 2, [&](std::size_t i) {
      if (omp_get_max_threads() != 2) ++wrong_threads;
      std::lock_guard<std::mutex> lock(m);
      seen.insert(i);
      return true;
    });
    EXPECT_EQ(started, 7u);
    EXPECT_EQ(seen, (std::multiset<std::size_t>{0, 1, 2, 3, 4, 5, 6})) << lanes << " lanes";
    EXPECT_EQ(wrong_threads, 0);
  }
  const int before = omp_get_max_threads();
  run_concurrently(2, 1, before + 1, [](std::size_t) { return true; });
  EXPECT_EQ(omp_get_max_threads(), before);  // the calling thread's count is restored
}

TEST(RunConcurrently, AFailureOrAnExceptionStartsNoNewJob) {
  // one lane: the jobs after the failed one never start
  std::vector<int> ran;
  EXPECT_EQ(run_concurrently(5, 1, 1, [&](std::size_t i) {
              ran.push_back(static_cast<int>(i));
              return i != 1;
            }),
            2u);
  EXPECT_EQ(ran, (std::vector<int>{0, 1}));
  // one lane: an exception likewise starts no new job, and reaches the caller
  ran.clear();
  EXPECT_THROW(run_concurrently(5, 1, 1,
                                [&](std::size_t i) -> bool {
                                  ran.push_back(static_cast<int>(i));
                                  throw std::runtime_error("job " + std::to_string(i));
                                }),
               std::runtime_error);
  EXPECT_EQ(ran, (std::vector<int>{0}));
  // two lanes: job 0 throws while job 1 runs on the other lane; the exception reaches the caller
  // only after job 1 has ended (each waits for the other to have started, so they are on two lanes)
  std::atomic<bool> zero_started{false}, one_started{false}, one_ended{false};
  auto wait_for = [](const std::atomic<bool>& flag) {
    while (!flag) std::this_thread::yield();
  };
  EXPECT_THROW(run_concurrently(50, 2, 1,
                                [&](std::size_t i) {
                                  if (i == 0) {
                                    zero_started = true;
                                    wait_for(one_started);
                                    throw std::runtime_error("job 0");
                                  }
                                  if (i == 1) {
                                    one_started = true;
                                    wait_for(zero_started);
                                    std::this_thread::sleep_for(std::chrono::milliseconds(50));
                                    one_ended = true;
                                  }
                                  return true;
                                }),
               std::runtime_error);
  EXPECT_TRUE(one_ended);
}

TEST(ConcurrentRuns, TwoAtATimeWriteWhatOneAfterTheOtherWrites) {
  const fs::path bin = require_example("water_drop");
  TempDir dir;
  const auto opts = kFourRuns + std::vector<std::string>{"--t-end", "0.002", "--output-every", "0.001",
                                                         "--checkpoint-every", "0.002"};
  const fs::path one = dir.path() / "one", two = dir.path() / "two";
  const Finished a = run(bin, opts + std::vector<std::string>{"--out", one.string(), "--threads", "1"}, dir.path());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_EQ(a.err.find("at a time"), std::string::npos) << a.err;  // one thread: one run at a time
  const Finished b = run(bin, opts + std::vector<std::string>{"--out", two.string(), "--threads", "2",
                                                              "--concurrent-runs", "2"},
                         dir.path());
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_NE(b.err.find("4 runs, 2 at a time on 1 thread each"), std::string::npos) << b.err;
  for (const std::string& r : kRunsInOrder) {
    SCOPED_TRACE(r);
    for (const char* file : {"diagnostics.csv", "drop_00002.vtp"}) {
      ASSERT_TRUE(fs::is_regular_file(one / r / file)) << file;
      EXPECT_EQ(file_bytes(one / r / file), file_bytes(two / r / file)) << file;
    }
  }
  // the summary lists the runs in their order, whichever ended first
  std::size_t at = 0;
  for (const std::string& r : kRunsInOrder) {
    const std::size_t next = b.out.find("\n" + (r.rfind("seed_", 0) == 0 ? r : r + " ") , at);
    ASSERT_NE(next, std::string::npos) << r << " after offset " << at << ":\n" << b.out;
    at = next + 1;
  }
}

TEST(ConcurrentRuns, SigintCheckpointsBothRunsInProgressAndStartsNoOther) {
  const fs::path bin = require_example("water_drop");
  TempDir dir;
  const fs::path out = dir.path() / "stopped";
  // long runs (t_end 1: 1e5 leapfrog steps each): SIGINT surely comes while the first two run
  const Spawned s = spawn(bin, kFourRuns + std::vector<std::string>{"--stepper", "leapfrog", "--dt", "1e-5", "--t-end",
                                                                   "1", "--output-every", "0.01", "--threads", "2",
                                                                   "--concurrent-runs", "2", "--out", out.string()},
                          dir.path());
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(out / "seed_control" / "drop_00000.vtp") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const Checkpoint c = interrupt_and_check(s, out / "seed_cleaned" / "drop_00000.vtp", "stopped by signal 2",
                                           out / "seed_cleaned", 1, std::chrono::milliseconds(200));
  const Checkpoint d = load_checkpoint(out / "seed_control" / "checkpoint.bin");
  EXPECT_GT(d.t, 0);
  EXPECT_LT(d.t, 1);
  EXPECT_FALSE(fs::exists(out / "cleaned"));  // the third and fourth runs never started
  EXPECT_FALSE(fs::exists(out / "control"));
}

// With pictures: a lane with no run left to start draws the pictures of the runs that have ended
// (Scene::run_pictures) while the other runs; the report draws the rest with its comparisons.
// Every picture is drawn once, and every one is there.
TEST(ConcurrentRuns, EveryPictureDrawnOnce) {
  const fs::path bin = require_example("water_drop");
  TempDir dir;
  const fs::path out = dir.path() / "pictures";
  const std::vector<std::string> opts = {"--spacing", "0.2", "--t-end", "0.004", "--output-every", "0.001",
                                         "--threads", "2", "--concurrent-runs", "2", "--out", out.string()};
  const Finished f = run(bin, opts, dir.path());
  ASSERT_EQ(f.exit_code, 0) << f.err;
  const std::string printed = f.out + f.err;
  std::vector<std::string> pictures = {"div_v.png", "density_error.png", "kinetic_energy.png"};
  for (const std::string& r : kRunsInOrder) pictures.insert(pictures.end(), {"semi_axes_" + r + ".png", "frames_" + r + ".png"});
  for (const std::string& png : pictures) {
    SCOPED_TRACE(png);
    EXPECT_TRUE(fs::is_regular_file(out / png));
    const std::string line = (out / png).string() + "\n";
    std::size_t count = 0;
    for (std::size_t at = printed.find(line); at != std::string::npos; at = printed.find(line, at + 1)) ++count;
    EXPECT_EQ(count, 1u) << printed;
  }
  EXPECT_EQ(printed.find("warning"), std::string::npos) << printed;
}
