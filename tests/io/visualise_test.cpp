// run_python: finds vis/ from SPHARK_SOURCE_DIR, reports failure with false (never aborts).
#include <gtest/gtest.h>

#include "sphark/io/visualise.hpp"

namespace sphark {
namespace {

TEST(RunPython, MissingScriptIsAWarningNotAnAbort) {
  ::testing::internal::CaptureStderr();
  EXPECT_FALSE(run_python("no_such_script.py", {}, false));
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(err.rfind("sphark: warning: vis/no_such_script.py: script not found", 0), 0u) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1);
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

}  // namespace
}  // namespace sphark
