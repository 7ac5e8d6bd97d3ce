// Progress line: the documented format, the ETA extrapolation and the rate limit.
#include <gtest/gtest.h>

#include <sstream>

#include "sphark/io/progress.hpp"

namespace sphark {
namespace {

TEST(ProgressReporter, FormatsTheDocumentedLine) {
  std::ostringstream out;
  ProgressReporter p(0.0, 0.1, 2, out);
  // 31.2 % done after 12 s: ETA = 12 * 0.688 / 0.312 = 26.46 s.
  EXPECT_EQ(p.format(0.0312, 1234, 2.1e-6, 12.0),
            "t = 0.0312 / 0.1 (31%)  step 1234  dt 2.1e-06  elapsed 12 s  ETA 26 s");
  // Start offset t0: fraction is (t - t0) / (t_end - t0) = 0.5, ETA = elapsed.
  ProgressReporter q(1.0, 3.0, 2, out);
  EXPECT_EQ(q.format(2.0, 10, 0.01, 30.0),
            "t = 2 / 3 (50%)  step 10  dt 0.01  elapsed 30 s  ETA 30 s");
  EXPECT_EQ(q.format(3.0, 20, 0.01, 4000.0), "t = 3 / 3 (100%)  step 20  dt 0.01  elapsed 67 min");
  EXPECT_TRUE(out.str().empty());
}

TEST(ProgressReporter, ALabelPrefixesEveryLine) {
  std::ostringstream out;
  ProgressReporter p(0.0, 1.0, 0, out);
  p.set_label("seed_control");
  EXPECT_EQ(p.format(0.5, 10, 0.1, 4.0), "seed_control: t = 0.5 / 1 (50%)  step 10  dt 0.1  elapsed 4 s  ETA 4 s");
  EXPECT_TRUE(p.update(0.5, 10, 0.1));
  p.finish();
  EXPECT_TRUE(out.str().starts_with("seed_control: t = 0.5 / 1 (50%)")) << out.str();
  EXPECT_TRUE(out.str().ends_with("\nseed_control: done: t = 0.5  steps 10  elapsed 0 s\n")) << out.str();
}

TEST(ProgressReporter, PrintsAtMostOncePerInterval) {
  std::ostringstream out;
  ProgressReporter slow(0, 1, 3600, out);
  for (int k = 1; k <= 100; ++k) EXPECT_FALSE(slow.update(k / 100.0, k, 0.01));
  EXPECT_TRUE(out.str().empty());
  slow.finish();
  EXPECT_EQ(out.str(), "done: t = 1  steps 100  elapsed 0 s\n");

  std::ostringstream out2;
  ProgressReporter every(0, 1, 0, out2);
  for (int k = 1; k <= 3; ++k) EXPECT_TRUE(every.update(k / 10.0, k, 0.1));
  int lines = 0;
  for (char c : out2.str()) lines += c == '\n';
  EXPECT_EQ(lines, 3);
  EXPECT_TRUE(out2.str().ends_with("t = 0.3 / 1 (30%)  step 3  dt 0.1  elapsed 0 s  ETA 0 s\n"))
      << out2.str();
}

}  // namespace
}  // namespace sphark
