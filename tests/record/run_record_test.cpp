// io/run_record.hpp: run.json is written when the record starts (outcome "running") and again
// at the end with the outcome, its reason and exactly the files written since the start.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>

#include "sphark/io/build_info.hpp"
#include "sphark/io/run_record.hpp"
#include "../support/temp_dir.hpp"

using namespace sphark;
namespace fs = std::filesystem;

namespace {
Json options() {
  Json o = Json::Object{};
  o["t-end"] = 0.1;
  o["out"] = "out";
  return o;
}

void touch(const fs::path& p, const std::string& text = "x") {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

std::vector<std::string> files_of(const Json& record) {
  std::vector<std::string> out;
  for (const Json& f : record.find("files")->as_array()) out.push_back(f.as_string());
  return out;
}
}  // namespace

TEST(RunRecord, StartsWithWhatRunsHowItWasBuiltAndEveryOption) {
  test::TempDir dir;
  RunRecord record(dir.path(), "water_drop", options(), 2, 1);
  const Json r = read_run_record(dir.path() / "run.json");
  const std::vector<std::string> keys = {"program", "version", "options", "threads", "ranks", "host",
                                         "working_directory", "start", "outcome"};
  ASSERT_EQ(r.as_object().size(), keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) EXPECT_EQ(r.as_object()[i].first, keys[i]);
  EXPECT_EQ(r.find("program")->as_string(), "water_drop");
  EXPECT_TRUE(*r.find("options") == options());
  EXPECT_EQ(r.find("threads")->as_number(), 2);
  EXPECT_EQ(r.find("ranks")->as_number(), 1);
  EXPECT_EQ(r.find("outcome")->as_string(), "running");
  EXPECT_TRUE(std::regex_match(r.find("start")->as_string(), std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z)")))
      << r.find("start")->as_string();
  const Json& v = *r.find("version");
  for (const char* k : {"version", "git_commit", "git_modified", "build_type", "sanitizers", "compiler", "sundials", "vtk"})
    EXPECT_NE(v.find(k), nullptr) << k;
  // built from a git checkout: its commit and a known modified state; from a tarball: unknown
  // (tests/scripts/build_info_test.sh checks both cases of cmake/build_info.cmake)
  const std::string commit = v.find("git_commit")->as_string();
  if (fs::exists(fs::path(SPHARK_SOURCE_DIR) / ".git")) {
    EXPECT_TRUE(std::regex_match(commit, std::regex("[0-9a-f]{40}"))) << commit;
    EXPECT_TRUE(v.find("git_modified")->is_bool());
  } else {
    EXPECT_EQ(commit, "unknown");
    EXPECT_EQ(v.find("git_modified")->as_string(), "unknown");
  }
  EXPECT_EQ(v.find("sundials")->as_string().rfind("6.", 0), 0u);
  EXPECT_EQ(v.find("vtk")->as_string().rfind("9.", 0), 0u);
  EXPECT_EQ(v.find("build_type")->as_string(), build_info().build_type);
  record.finish(RecordOutcome::ok);
}

TEST(RunRecord, EndsWithOutcomeReasonAndExactlyTheFilesWrittenSinceTheStart) {
  test::TempDir dir;
  touch(dir.path() / "old.csv");  // an earlier run's file, left in the folder
  fs::last_write_time(dir.path() / "old.csv", fs::file_time_type::clock::now() - std::chrono::hours(1));
  RunRecord record(dir.path(), "water_drop", options(), 1);
  touch(dir.path() / "cleaned" / "diagnostics.csv");
  touch(dir.path() / "cleaned" / ".drop.pvd.tmp.123");  // a temporary of an atomic write
  touch(dir.path() / "summary.csv");
  record.set("variant", "cleaned");
  EXPECT_EQ(record.finish_with_exit_code(0), 0);
  const Json r = read_run_record(record.path());
  EXPECT_EQ(r.find("outcome")->as_string(), "ok");
  EXPECT_EQ(r.find("reason"), nullptr);
  EXPECT_EQ(files_of(r), (std::vector<std::string>{"cleaned/diagnostics.csv", "run.json", "summary.csv"}));
  EXPECT_EQ(r.find("variant")->as_string(), "cleaned");
  EXPECT_EQ(r.as_object()[3].first, "variant");  // set() entries stand before "threads"
  EXPECT_NE(r.find("end"), nullptr);
  EXPECT_GE(r.find("wall_seconds")->as_number(), 0);
  record.finish(RecordOutcome::failed, "late");  // the first outcome counts
  EXPECT_EQ(read_run_record(record.path()).find("outcome")->as_string(), "ok");
}

TEST(RunRecord, ExitCodesMapToOutcomes) {
  const std::vector<std::tuple<int, std::string, std::string, std::string>> cases = {
      {130, "", "stopped", "SIGINT"},
      {143, "", "stopped", "SIGTERM"},
      {3, "cleaned run: min_dt reached", "failed", "cleaned run: min_dt reached"},
      {1, "", "failed", "exit code 1"}};
  for (const auto& [code, reason, outcome, why] : cases) {
    test::TempDir dir;
    RunRecord record(dir.path(), "p", options(), 1);
    EXPECT_EQ(record.finish_with_exit_code(code, reason), code);
    const Json r = read_run_record(record.path());
    EXPECT_EQ(r.find("outcome")->as_string(), outcome) << code;
    EXPECT_EQ(r.find("reason")->as_string(), why) << code;
  }
}

TEST(RunRecord, ARecordLeftUnfinishedSaysSo) {
  test::TempDir dir;
  { RunRecord record(dir.path(), "p", options(), 1); }
  const Json r = read_run_record(dir.path() / "run.json");
  EXPECT_EQ(r.find("outcome")->as_string(), "failed");
  EXPECT_EQ(r.find("reason")->as_string(), "ended without recording an outcome");
  // a moved-from record writes nothing; the one it moved into finishes
  test::TempDir other;
  {
    RunRecord a(other.path(), "p", options(), 1);
    RunRecord b(std::move(a));
    EXPECT_TRUE(a.finished());
    b.finish(RecordOutcome::stopped, "SIGTERM");
  }
  EXPECT_EQ(read_run_record(other.path() / "run.json").find("outcome")->as_string(), "stopped");
}

TEST(RunRecord, AnUnwritableFolderThrowsAtTheStart) {
  EXPECT_THROW(RunRecord(fs::path("/nonexistent/sphark"), "p", options(), 1), std::runtime_error);
  EXPECT_THROW(read_run_record("/nonexistent/run.json"), std::runtime_error);
}
