// A run killed (SIGKILL) in the middle of writing leaves only complete output files: every
// visible .vtp reads back whole, and the .pvd is valid and lists only files that exist.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include "sphark/io/csv_writer.hpp"
#include "sphark/io/vtk_series.hpp"
#include "sphark/io/vtp_reader.hpp"
#include "../support/temp_dir.hpp"

namespace sphark {
namespace {

constexpr std::size_t kPoints = 100000;

TEST(KilledRun, LeavesOnlyCompleteFiles) {
  test::TempDir dir;
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {  // writer: frames (and a text file) as fast as it can, until killed
    std::vector<Real> pos(2 * kPoints), rho(kPoints);
    VtkSeriesWriter w(dir.path(), "run");
    for (int k = 0;; ++k) {
      for (std::size_t i = 0; i < kPoints; ++i) {
        pos[2 * i] = Real(i) + k;
        pos[2 * i + 1] = -Real(i);
        rho[i] = 1000 + k + 1e-3 * i;
      }
      w.write(ParticleFrame{2, kPoints, pos.data(), {{"density", rho.data(), 1}}}, 0.1 * k);
      write_file_atomically(dir.path() / "summary.txt", std::string(200000 + k, 'x'));
    }
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  ASSERT_EQ(::kill(child, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status));

  std::size_t frames = 0, temporaries = 0;
  for (const auto& name : dir.entries()) {
    if (name.front() == '.') {  // an interrupted write's temporary (hidden, never renamed)
      ++temporaries;
      continue;
    }
    const auto path = dir.path() / name;
    if (path.extension() == ".vtp") {
      const VtpContents c = read_vtp(path);  // throws if truncated
      ASSERT_EQ(c.count, kPoints) << name;
      const int k = std::stoi(name.substr(4, 5));
      ASSERT_EQ(c.find("density")->values[kPoints - 1], 1000 + k + 1e-3 * (kPoints - 1)) << name;
      ++frames;
    } else if (name == "summary.txt") {
      EXPECT_GE(std::filesystem::file_size(path), 200000u);
    } else {
      EXPECT_EQ(name, "run.pvd");
    }
  }
  std::printf("killed after %zu frames, %zu temporary file(s) left\n", frames, temporaries);
  EXPECT_LE(temporaries, 1u);  // at most the one file being written at the kill
  ASSERT_GE(frames, 1u) << "the writer produced no frame in 700 ms";
  std::ifstream in(dir.path() / "run.pvd");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string pvd = ss.str();
  EXPECT_NE(pvd.find("</VTKFile>"), std::string::npos);
  const std::regex ds(R"re(file="([^"]+)")re");
  std::size_t listed = 0;
  for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), ds); it != std::sregex_iterator();
       ++it, ++listed) {
    EXPECT_TRUE(std::filesystem::exists(dir.path() / (*it)[1].str())) << (*it)[1].str();
  }
  // The .pvd is rewritten after each frame: it lists every frame, or all but the newest.
  EXPECT_TRUE(listed == frames || listed + 1 == frames) << listed << " vs " << frames;
}

}  // namespace
}  // namespace sphark
