// stepper_study's matrix survives an interruption: SIGINT stops between cases with
// work_precision.csv complete (the rows done so far, written atomically), and a rerun with
// --resume keeps those rows byte for byte and runs only the missing cases. (An external SIGINT
// to a running program is tested on the time loops: ExampleRuns.*, MhdRuns.*.)
#include <gtest/gtest.h>

#include <set>
#include <sstream>

#include "../support/temp_dir.hpp"
#include "run_example.hpp"

using namespace sphark::test;
namespace fs = std::filesystem;

namespace {
std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}
}  // namespace

TEST(StudyResume, SigintKeepsCompleteRowsAndResumeRunsOnlyTheMissingCases) {
  const fs::path bin = require_example("stepper_study");
  TempDir dir;
  const fs::path out = dir.path() / "study";
  // 1 adaptive + 3 leapfrog cases on a 52-particle drop (small: the sanitizer pass runs it too)
  const std::vector<std::string> args = {"--what", "matrix", "--spacing", "0.25", "--t-end", "0.01", "--outputs", "5",
                                         "--methods", "BOGACKI_SHAMPINE_4_2_3", "--modes", "capped", "--cap-cfl", "1", "--rtols", "1e-3",
                                         "--fixed-methods", "none", "--leapfrog-cfls", "0.4,0.2,0.1",
                                         "--reference-rtol", "1e-5", "--no-render", "--threads", "1", "--out",
                                         out.string()};
  // SIGINT after the second case, sent by the study itself (deterministic; the real handler)
  std::vector<std::string> interrupted = args;
  interrupted.insert(interrupted.end(), {"--raise-sigint-after", "2"});
  const Finished f = run(bin, interrupted, dir.path());
  EXPECT_EQ(f.exit_code, 128 + SIGINT) << f.err;
  EXPECT_NE(f.err.find("stopped by signal 2"), std::string::npos) << f.err;
  EXPECT_NE(f.err.find("--resume"), std::string::npos) << f.err;
  const fs::path csv = out / "work_precision.csv";
  const std::string before = slurp(csv);
  const std::vector<std::string> rows_before = lines(before);
  ASSERT_EQ(rows_before.size(), 3u);  // header + the 2 cases done
  EXPECT_EQ(before.back(), '\n');
  for (const auto& e : fs::directory_iterator(out))
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();

  std::vector<std::string> resume = args;
  resume.push_back("--resume");
  const Finished r = run(bin, resume, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("--resume: 2 rows"), std::string::npos) << r.out;
  const std::vector<std::string> rows_after = lines(slurp(csv));
  ASSERT_GT(rows_after.size(), rows_before.size());
  for (std::size_t k = 0; k < rows_before.size(); ++k) EXPECT_EQ(rows_after[k], rows_before[k]);
  // only the missing cases ran again (every case prints one line with its cpu time; the first two
  // are the reference run and its check), and no case has two rows
  std::size_t printed = 0;
  for (const std::string& l : lines(r.out))
    if (l.find(" cpu ") != std::string::npos) ++printed;
  EXPECT_EQ(rows_before.size() + printed - 2, rows_after.size());
  std::set<std::string> cases;
  for (std::size_t k = 1; k < rows_after.size(); ++k) {
    std::vector<std::string> c;
    std::stringstream in(rows_after[k]);
    for (std::string cell; std::getline(in, cell, ',');) c.push_back(cell);
    ASSERT_GT(c.size(), 10u) << rows_after[k];
    cases.insert(c[1] + "," + c[2] + "," + c[9] + "," + c[10]);  // method, rtol, mode, cfl
  }
  EXPECT_EQ(cases.size(), rows_after.size() - 1);
}
