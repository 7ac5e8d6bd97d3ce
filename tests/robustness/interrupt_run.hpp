#pragma once
// SIGINT to a running example and the checks every example's stop must pass (docs/robustness.md).
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

#include "run_example.hpp"
#include "sphark/run/checkpoint.hpp"

namespace sphark::test {

// Waits (at most 60 s) until `appears` exists, then `settle` more, sends SIGINT and checks the
// stopped run: exit code 128 + SIGINT, `message` on stderr, a checkpoint `run_dir`/checkpoint.bin
// with 0 < t < t_end, and no temporary file left in run_dir. Returns the checkpoint.
inline Checkpoint interrupt_and_check(const Spawned& s, const std::filesystem::path& appears, const std::string& message,
                                      const std::filesystem::path& run_dir, Real t_end,
                                      std::chrono::milliseconds settle = std::chrono::milliseconds(0)) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!std::filesystem::exists(appears) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::this_thread::sleep_for(settle);
  kill(s.pid, SIGINT);
  const Finished f = wait_for(s);
  EXPECT_EQ(f.exit_code, 128 + SIGINT) << f.err;
  EXPECT_NE(f.err.find(message), std::string::npos) << f.err;
  const Checkpoint c = load_checkpoint(run_dir / "checkpoint.bin");
  EXPECT_GT(c.t, 0);
  EXPECT_LT(c.t, t_end);
  for (const auto& e : std::filesystem::directory_iterator(run_dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();
  return c;
}

}  // namespace sphark::test
