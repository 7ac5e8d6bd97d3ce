// run_python: finds vis/ from SPHARK_SOURCE_DIR, reports failure with false (never aborts).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>

#include "sphark/io/csv_writer.hpp"
#include "sphark/io/visualise.hpp"
#include "../support/file_bytes.hpp"
#include "sphark/io/vtk_series.hpp"
#include "../support/temp_dir.hpp"

namespace sphark {
namespace {

TEST(RunPython, MissingScriptIsAWarningNotAnAbort) {
  ::testing::internal::CaptureStderr();
  EXPECT_FALSE(run_python("no_such_script.py", {}, false));
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(err.rfind("sphark: warning: vis/no_such_script.py: script not found", 0), 0u) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1);
}

TEST(RunProcess, TimeoutKillsTheProcessGroup) {
  const auto t0 = std::chrono::steady_clock::now();
  // A shell whose child (sleep) shares its process group: both must go.
  const ProcessResult r = run_process({"/bin/sh", "-c", "sleep 30; exit 0"}, 0.3);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.error, "still running after 0.3 s, killed");
  EXPECT_LT(s, 3.0);
  EXPECT_TRUE(run_process({"/bin/sh", "-c", "exit 0"}, 10).ok);
  EXPECT_EQ(run_process({"/bin/sh", "-c", "exit 3"}, 10).error, "exited with status 3");
  EXPECT_EQ(run_process({"/bin/sh", "-c", "kill -9 $$"}, 10).error, "killed by signal 9");
  EXPECT_EQ(run_process({"/no/such/program"}, 10).error,
            "cannot start /no/such/program: No such file or directory");
}

TEST(RunPython, ExitStatusDecidesTheResult) {
  ASSERT_TRUE(std::filesystem::is_regular_file(vis_dir() / "charts.py"));
  EXPECT_TRUE(run_python("charts.py", {"--help"}, false));
  ::testing::internal::CaptureStderr();
  EXPECT_FALSE(run_python("charts.py", {"--no-such-flag"}, false));
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("sphark: warning: vis/charts.py: exited with status 2"), std::string::npos)
      << err;
}

// Width and height from a PNG's IHDR chunk; {0, 0} if the file is not a PNG.
std::pair<std::uint32_t, std::uint32_t> png_size(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  unsigned char h[24] = {};
  in.read(reinterpret_cast<char*>(h), sizeof h);
  const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (!in || !std::equal(sig, sig + 8, h) || std::string(h + 12, h + 16) != "IHDR") return {0, 0};
  auto be32 = [&](int o) {
    return std::uint32_t(h[o]) << 24 | std::uint32_t(h[o + 1]) << 16 |
           std::uint32_t(h[o + 2]) << 8 | std::uint32_t(h[o + 3]);
  };
  return {be32(16), be32(20)};
}

TEST(RunPython, ChartFromCsvWriterOutput) {
  test::TempDir dir;
  {
    CsvWriter csv(dir.path() / "diag.csv", {"t", "mean_abs_div_v", "energy"});
    for (int k = 0; k <= 50; ++k) csv.row({0.02 * k, std::exp(-4.0 * 0.02 * k), 1.0});
  }
  const auto png = dir.path() / "div.png";
  ASSERT_TRUE(run_python("charts.py", {"--csv", (dir.path() / "diag.csv").string() + ":run",
                                       "--x", "t", "--y", "mean_abs_div_v", "--logy",
                                       "--y-extra", "energy", "--out", png.string()},
                         false));
  // 6.4 x 4.4 inches at 150 dpi.
  EXPECT_EQ(png_size(png), (std::pair<std::uint32_t, std::uint32_t>{960, 660}));
}

TEST(RunPython, RendersAFrameFromVtkSeriesWriter) {
  test::TempDir dir;
  std::vector<Real> pos, rho;
  for (int i = 0; i < 20; ++i) {
    for (int j = 0; j < 10; ++j) {
      pos.insert(pos.end(), {0.05 * i, 0.05 * j});
      rho.push_back(1000 + i);
    }
  }
  VtkSeriesWriter w(dir.path(), "frame");
  w.write(ParticleFrame{2, rho.size(), pos.data(), {{"density", rho.data(), 1}}}, 0.5);
  const auto png = dir.path() / "frame.png";
  ASSERT_TRUE(run_python("render_particles.py",
                         {w.pvd_path().string(), "--array", "density", "--out", png.string()},
                         true));
  const auto [width, height] = png_size(png);
  EXPECT_GT(width, 400u);
  EXPECT_GT(height, 200u);
  // A missing array is the script's usage error, reported as a warning here.
  ::testing::internal::CaptureStderr();
  EXPECT_FALSE(run_python("render_particles.py",
                          {w.pvd_path().string(), "--array", "nope", "--out", png.string()},
                          false));  // fails before rendering: no display needed
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("no point array 'nope'"), std::string::npos) << err;
  EXPECT_NE(err.find("sphark: warning: vis/render_particles.py: exited with status 2"),
            std::string::npos) << err;
  // The colour range's percentile must leave a range: 50 % from both ends leaves none.
  ::testing::internal::CaptureStderr();
  EXPECT_FALSE(run_python("render_particles.py",
                          {w.pvd_path().string(), "--array", "density", "--clip", "50", "--out", png.string()},
                          false));
  const std::string clip_err = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(clip_err.find("--clip: need 0 <= P < 50 (got 50)"), std::string::npos) << clip_err;
}

// --clip P colours by the P and 100 - P percentiles of the values: 201 values, two spikes
// (-1e6, 1e6) and 1 .. 199 between, so at P = 0.5 (index 0.005 x 200 = 1 and 199 of the sorted
// values, no interpolation) the range is exactly [1, 199]: the same picture as --range 1 199,
// byte for byte, and not the picture of the full range (--clip 0).
TEST(RunPython, ClippedColourRangeIsThePercentileRange) {
  test::TempDir dir;
  std::vector<Real> pos, value;
  for (int k = 0; k < 201; ++k) {
    pos.insert(pos.end(), {0.05 * (k % 20), 0.05 * (k / 20)});
    value.push_back(k == 0 ? -1e6 : k == 200 ? 1e6 : Real(k));
  }
  VtkSeriesWriter w(dir.path(), "frame");
  w.write(ParticleFrame{2, value.size(), pos.data(), {{"value", value.data(), 1}}}, 0.0);
  const auto draw = [&](const std::string& name, const std::vector<std::string>& range) {
    std::vector<std::string> args = {w.pvd_path().string(), "--array", "value", "--out", (dir.path() / name).string()};
    args.insert(args.end(), range.begin(), range.end());
    EXPECT_TRUE(run_python("render_particles.py", args, true)) << name;
    return test::file_bytes(dir.path() / name);
  };
  const std::string clipped = draw("clip.png", {"--clip", "0.5"});
  ASSERT_GT(clipped.size(), 1000u);
  EXPECT_EQ(clipped, draw("range.png", {"--range", "1", "199"}));
  EXPECT_NE(clipped, draw("full.png", {"--clip", "0"}));
}

// One Python process for several pictures: every job runs even after a failed one, the result
// is false then, and the failed job is named.
TEST(RunPythonBatch, EveryJobRunsAndAFailedOneIsNamed) {
  test::TempDir dir;
  {
    CsvWriter csv(dir.path() / "diag.csv", {"t", "a", "b"});
    for (int k = 0; k <= 20; ++k) csv.row({0.05 * k, 1.0 + k, 2.0 * k});
  }
  const std::string csv = (dir.path() / "diag.csv").string();
  const auto png_a = dir.path() / "a.png", png_b = dir.path() / "b.png";
  const auto chart = [&](const std::string& y, const std::filesystem::path& png) {
    return PythonJob{"charts.py", {"--csv", csv + ":run", "--x", "t", "--y", y, "--styles=--", "--out", png.string()}};
  };
  ASSERT_TRUE(run_python_batch({chart("a", png_a), chart("b", png_b)}, false));
  EXPECT_EQ(png_size(png_a), (std::pair<std::uint32_t, std::uint32_t>{960, 660}));
  EXPECT_EQ(png_size(png_b), (std::pair<std::uint32_t, std::uint32_t>{960, 660}));
  std::filesystem::remove(png_b);
  ::testing::internal::CaptureStderr();
  EXPECT_FALSE(run_python_batch({chart("no_such_column", png_a), chart("b", png_b)}, false));
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("no column 'no_such_column'"), std::string::npos) << err;
  EXPECT_NE(err.find("batch.py: charts.py exited with status 2"), std::string::npos) << err;
  EXPECT_NE(err.find("sphark: warning: vis/batch.py: exited with status 1"), std::string::npos) << err;
  EXPECT_EQ(png_size(png_b), (std::pair<std::uint32_t, std::uint32_t>{960, 660}));  // the job after the failed one
  ::testing::internal::CaptureStderr();
  EXPECT_FALSE(run_python_batch({{"../charts.py", {}}}, false));  // only scripts of vis/
  EXPECT_NE(::testing::internal::GetCapturedStderr().find("expected a script name of vis/"), std::string::npos);
  EXPECT_TRUE(run_python_batch({}, false));  // nothing to draw: nothing started
}

// The batch's workers draw the same pictures as one process alone, byte for byte.
TEST(RunPythonBatch, WorkersDrawTheSamePicturesAsOneProcess) {
  test::TempDir dir;
  {
    CsvWriter csv(dir.path() / "diag.csv", {"t", "a", "b", "c"});
    for (int k = 0; k <= 20; ++k) csv.row({0.05 * k, 1.0 + k, 2.0 * k, std::sin(0.3 * k)});
  }
  const std::string csv = (dir.path() / "diag.csv").string();
  const auto jobs_into = [&](const std::string& tag) {
    std::vector<PythonJob> jobs;
    for (const char* y : {"a", "b", "c"})
      jobs.push_back({"charts.py", {"--csv", csv + ":run", "--x", "t", "--y", y, "--out",
                                    (dir.path() / (tag + y + ".png")).string()}});
    return jobs;
  };
  ASSERT_TRUE(run_python_batch(jobs_into("one_"), false, 600, 1));
  ASSERT_TRUE(run_python_batch(jobs_into("two_"), false, 600, 2));
  for (const char* y : {"a", "b", "c"}) {
    const std::string one = test::file_bytes(dir.path() / (std::string("one_") + y + ".png"));
    EXPECT_GT(one.size(), 1000u) << y;
    EXPECT_EQ(one, test::file_bytes(dir.path() / (std::string("two_") + y + ".png"))) << y;
  }
}

// --styles: one matplotlib line style per line; more styles than lines is the usage error.
TEST(RunPython, ChartStylesMustNotOutnumberTheLines) {
  test::TempDir dir;
  {
    CsvWriter csv(dir.path() / "diag.csv", {"t", "a"});
    for (int k = 0; k <= 5; ++k) csv.row({0.1 * k, 1.0 * k});
  }
  ::testing::internal::CaptureStderr();
  EXPECT_FALSE(run_python("charts.py", {"--csv", (dir.path() / "diag.csv").string(), "--x", "t", "--y", "a",
                                        "--styles=-,--", "--out", (dir.path() / "a.png").string()},
                          false));
  EXPECT_NE(::testing::internal::GetCapturedStderr().find("--styles: 2 styles for 1 lines"), std::string::npos);
}

}  // namespace
}  // namespace sphark
