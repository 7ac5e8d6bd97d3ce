#pragma once
// A run split by a restart against the same run uninterrupted: the pair every restart test
// compares (checkpoint/restart, issue #21).
#include <filesystem>
#include <string>
#include <vector>

#include "run_example.hpp"
#include "sphark/run/checkpoint.hpp"

namespace sphark::test {

// An uninterrupted run to t_end (<dir>/<tag>_whole) and a run to t_split restarted to t_end from
// its checkpoint `checkpoint` (relative to the output directory) into <dir>/<tag>_second. Returns
// the two final checkpoints (whole, restarted); false on a failed run.
inline bool split_run(const std::string& program, const std::vector<std::string>& opts, const std::filesystem::path& dir,
                      const std::string& tag, const std::string& checkpoint, Checkpoint& whole_end,
                      Checkpoint& restarted_end, const std::string& t_split = "0.1", const std::string& t_end = "0.2") {
  const std::filesystem::path whole = dir / (tag + "_whole"), first = dir / (tag + "_first"),
                              second = dir / (tag + "_second");
  const auto with = [&opts](std::vector<std::string> more) {
    more.insert(more.begin(), opts.begin(), opts.end());
    return more;
  };
  const Finished w = run(require_example(program), with({"--out", whole.string(), "--t-end", t_end}), dir);
  const Finished f = run(require_example(program), with({"--out", first.string(), "--t-end", t_split}), dir);
  const Finished r = run(require_example(program),
                         {"--restart", (first / checkpoint).string(), "--out", second.string(), "--t-end", t_end}, dir);
  EXPECT_EQ(w.exit_code, 0) << w.err;
  EXPECT_EQ(f.exit_code, 0) << f.err;
  EXPECT_EQ(r.exit_code, 0) << r.err;
  if (w.exit_code != 0 || f.exit_code != 0 || r.exit_code != 0) return false;
  whole_end = load_checkpoint(whole / checkpoint);
  restarted_end = load_checkpoint(second / checkpoint);
  return true;
}

}  // namespace sphark::test
