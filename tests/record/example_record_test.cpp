// The water drop example's run record end to end (tiny drops, 80 particles): run.json names
// every option the program takes and how the run ended (ok, failed, stopped); `--config
// run.json` re-runs it bit for bit, the command line overriding the config; a bad config is
// one line and exit 2 with nothing written; view.pvsm names only files and arrays that exist.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <regex>
#include <thread>

#include "../robustness/run_example.hpp"
#include "../support/temp_dir.hpp"
#include "sphark/io/paraview_state.hpp"
#include "sphark/io/run_record.hpp"
#include "sphark/io/vtp_reader.hpp"

using namespace sphark;
using namespace sphark::test;
namespace fs = std::filesystem;

namespace {
const std::vector<std::string> kTiny = {"--spacing", "0.2", "--no-render", "--threads", "1", "--t-end", "0.002",
                                        "--output-every", "0.001"};

std::vector<std::string> operator+(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

fs::path binary(const std::string& name) {
  const fs::path bin = example_binary(name);
  if (!fs::exists(bin)) ADD_FAILURE() << bin << " not built";
  return bin;
}

// The option names (without "--") that `program --help` lists, --help and --config aside.
std::vector<std::string> help_options(const fs::path& bin, const fs::path& logs) {
  const Finished f = run(bin, {"--help"}, logs);
  std::vector<std::string> names;
  const std::regex option(R"(^  --([a-z0-9][a-z0-9-]*))");
  std::istringstream in(f.out);
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (std::regex_search(line, m, option) && m[1] != "help" && m[1] != "config") names.push_back(m[1]);
  }
  return names;
}

std::vector<std::string> strings(const Json& array) {
  std::vector<std::string> out;
  for (const Json& e : array.as_array()) out.push_back(e.as_string());
  return out;
}

std::size_t count(const std::string& s, char c) { return static_cast<std::size_t>(std::count(s.begin(), s.end(), c)); }
}  // namespace

TEST(ExampleRecord, RunJsonHoldsEveryOptionTheFilesAndTheOutcome) {
  const fs::path bin = binary("water_drop");
  TempDir dir;
  const fs::path out = dir.path() / "ok";
  const Finished f = run(bin, kTiny + std::vector<std::string>{"--out", out.string(), "--amplitude", "50"}, dir.path());
  ASSERT_EQ(f.exit_code, 0) << f.err;
  const Json r = read_run_record(out / "run.json");
  EXPECT_EQ(r.find("program")->as_string(), "water_drop");
  const std::vector<std::string> names = help_options(bin, dir.path());
  ASSERT_GT(names.size(), 20u);
  const Json& options = *r.find("options");
  EXPECT_EQ(options.as_object().size(), names.size());
  for (const auto& n : names) EXPECT_NE(options.find(n), nullptr) << n << " missing from run.json";
  EXPECT_EQ(options.find("amplitude")->as_number(), 50);
  EXPECT_EQ(options.find("rtol")->as_number(), 1e-2);  // a default, recorded too
  EXPECT_EQ(options.find("step-cap")->as_bool(), false);
  EXPECT_EQ(strings(*r.find("options_given")),
            (std::vector<std::string>{"out", "t-end", "output-every", "threads", "no-render", "amplitude", "spacing"}));
  EXPECT_EQ(r.find("threads")->as_number(), 1);
  EXPECT_EQ(r.find("outcome")->as_string(), "ok");
  EXPECT_EQ(r.find("reason"), nullptr);
  const std::vector<std::string> files = strings(*r.find("files"));
  for (const char* expected : {"seed_cleaned/diagnostics.csv", "seed_control/drop.pvd", "cleaned/diagnostics.csv",
                               "cleaned/drop.pvd", "cleaned/drop_00002.vtp", "control/diagnostics.csv", "run.json",
                               "summary.csv", "view.pvsm"})
    EXPECT_NE(std::find(files.begin(), files.end(), expected), files.end()) << expected;
  for (const auto& file : files) EXPECT_TRUE(fs::is_regular_file(out / file)) << file;
  std::size_t on_disk = 0;
  for (const auto& e : fs::recursive_directory_iterator(out)) on_disk += e.is_regular_file();
  EXPECT_EQ(files.size(), on_disk);  // a fresh folder: every file in it was written by this run
  // the view: the seed's cleaned | control, delta-SPH's cleaned | control, coloured by pressure,
  // every named file and array present
  const ParaViewStateRefs v = read_paraview_state(out / "view.pvsm");
  EXPECT_EQ(v.files, (std::vector<std::string>{"seed_cleaned/drop.pvd", "seed_control/drop.pvd", "cleaned/drop.pvd",
                                               "control/drop.pvd"}));
  ASSERT_EQ(v.colourings.size(), 4u);
  for (const auto& c : v.colourings) {
    EXPECT_EQ(c.array, "pressure");
    EXPECT_EQ(c.association, "points");
    for (const auto& [t, frame] : read_pvd(out / c.reader_file))
      EXPECT_NE(read_vtp(out / fs::path(c.reader_file).parent_path() / frame).find(c.array), nullptr) << frame;
  }
}

TEST(ExampleRecord, AReRunFromRunJsonIsBitIdenticalAndTheCommandLineOverridesIt) {
  const fs::path bin = binary("water_drop");
  TempDir dir;
  const fs::path a = dir.path() / "a", b = dir.path() / "b", c = dir.path() / "c";
  ASSERT_EQ(run(bin, kTiny + std::vector<std::string>{"--out", a.string(), "--rtol", "3.7e-5", "--omega", "90.5",
                                                      "--kernel", "cubic"},
                dir.path()).exit_code, 0);
  const Finished again = run(bin, {"--config", (a / "run.json").string(), "--out", b.string()}, dir.path());
  ASSERT_EQ(again.exit_code, 0) << again.err;
  for (const char* run_dir : {"seed_cleaned", "seed_control", "cleaned", "control"}) {
    const std::string da = slurp(a / run_dir / "diagnostics.csv"), db = slurp(b / run_dir / "diagnostics.csv");
    EXPECT_GT(count(da, '\n'), 10u);
    EXPECT_EQ(da, db) << run_dir;  // bit for bit: every value is written with %.17g
  }
  Json oa = *read_run_record(a / "run.json").find("options"), ob = *read_run_record(b / "run.json").find("options");
  EXPECT_EQ(ob.find("out")->as_string(), b.string());
  oa["out"] = b.string();
  EXPECT_TRUE(oa == ob);
  EXPECT_EQ(strings(*read_run_record(b / "run.json").find("config_files")), std::vector<std::string>{(a / "run.json").string()});
  // command line over config: a shorter run, the rest as recorded
  ASSERT_EQ(run(bin, {"--t-end", "0.001", "--config", (a / "run.json").string(), "--out", c.string()}, dir.path()).exit_code, 0);
  const Json rc = read_run_record(c / "run.json");
  EXPECT_EQ(rc.find("options")->find("t-end")->as_number(), 0.001);
  EXPECT_EQ(rc.find("options")->find("rtol")->as_number(), 3.7e-5);
  EXPECT_EQ(rc.find("options")->find("kernel")->as_string(), "cubic");
  const std::string dc = slurp(c / "cleaned" / "diagnostics.csv"), da = slurp(a / "cleaned" / "diagnostics.csv");
  EXPECT_LT(dc.size(), da.size());
  EXPECT_EQ(da.compare(0, dc.size(), dc), 0);  // the same run, stopped earlier (fixed diagnostics grid)
}

TEST(ExampleRecord, ABadConfigIsOneLineAndExitTwoWithNothingWritten) {
  const fs::path bin = binary("water_drop");
  TempDir dir;
  const fs::path cfg = dir.path() / "bad.json";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"options": {"t_end": 0.1}})", "water_drop: --t_end: unknown option in config '" + cfg.string() + "' (try --help)"},
      {R"({"spacing": "0.2"})", "water_drop: --spacing: bad value '\"0.2\"' in config '" + cfg.string() + "' (expected a positive real number)"},
      {R"({"h-factor": 9})", "water_drop: --h-factor: bad value '9' in config '" + cfg.string() + "' (expected a real number in [0.8, 4])"},
      {R"({"cleaning": true})", "water_drop: --cleaning: bad value 'true' in config '" + cfg.string() + "' (expected one of: on, off, both)"},
      {R"({"t-end": 0.1)", "water_drop: --config: '" + cfg.string() + "': line 1, column 14: expected ',' or '}'"},
      {R"({"program": "orszag_tang", "options": {}})", "water_drop: --config: '" + cfg.string() + "' records a run of orszag_tang, not water_drop"},
  };
  for (const auto& [text, line] : cases) {
    std::ofstream(cfg) << text;
    const fs::path out = dir.path() / "never";
    const Finished f = run(bin, {"--config", cfg.string(), "--out", out.string()}, dir.path());
    EXPECT_EQ(f.exit_code, 2) << text;
    EXPECT_EQ(f.err, line + "\n") << text;
    EXPECT_FALSE(fs::exists(out)) << text;  // nothing written
  }
  const Finished missing = run(bin, {"--config", (dir.path() / "none.json").string()}, dir.path());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(count(missing.err, '\n'), 1u) << missing.err;
}

TEST(ExampleRecord, AFailedAndAStoppedRunSaySoAndWhy) {
  const fs::path bin = binary("water_drop");
  TempDir dir;
  const fs::path failed = dir.path() / "failed";
  const Finished f = run(bin, kTiny + std::vector<std::string>{"--out", failed.string(), "--scheme", "delta-sph",
                                                               "--cleaning", "on", "--inject-nan-at", "0.0015"}, dir.path());
  ASSERT_EQ(f.exit_code, 3) << f.err;
  const Json rf = read_run_record(failed / "run.json");
  EXPECT_EQ(rf.find("outcome")->as_string(), "failed");
  const std::string why = rf.find("reason")->as_string();
  EXPECT_NE(why.find("non-finite time derivative"), std::string::npos) << why;
  EXPECT_NE(f.err.find(why), std::string::npos) << why << "\n" << f.err;  // the reason the program printed
  const std::vector<std::string> files = strings(*rf.find("files"));
  EXPECT_NE(std::find(files.begin(), files.end(), "cleaned/checkpoint.bin"), files.end());  // the last good state
  // SIGINT mid-run (1e5 leapfrog steps: surely mid-run)
  const fs::path stopped = dir.path() / "stopped";
  const Spawned s = spawn(bin, {"--spacing", "0.2", "--no-render", "--threads", "1", "--scheme", "delta-sph", "--cleaning", "on", "--stepper",
                                "leapfrog", "--dt", "1e-5", "--t-end", "1", "--output-every", "0.01", "--out", stopped.string()},
                          dir.path());
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(stopped / "cleaned" / "drop_00001.vtp") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_EQ(read_run_record(stopped / "run.json").find("outcome")->as_string(), "running");  // written before computing
  kill(s.pid, SIGINT);
  EXPECT_EQ(wait_for(s).exit_code, 128 + SIGINT);
  const Json rs = read_run_record(stopped / "run.json");
  EXPECT_EQ(rs.find("outcome")->as_string(), "stopped");
  EXPECT_EQ(rs.find("reason")->as_string(), "SIGINT");
}

TEST(ExampleRecord, ADefaultOutputIntervalFollowsAShortRun) {  // issue #21
  TempDir dir;
  const fs::path out = dir.path() / "short";
  const Finished f = run(binary("water_drop"), {"--spacing", "0.2", "--no-render", "--threads", "1", "--cleaning", "on",
                                                "--t-end", "0.0005", "--out", out.string()}, dir.path());
  ASSERT_EQ(f.exit_code, 0) << f.err;  // defaults: --output-every 0.002, --diagnostics-every 1e-4 ...
  const Json record = read_run_record(out / "run.json");
  const Json& o = *record.find("options");
  EXPECT_EQ(o.find("output-every")->as_number(), 0.0005);  // ... the first followed the run
  EXPECT_EQ(o.find("diagnostics-every")->as_number(), 1e-4);
  const Finished given = run(binary("water_drop"), {"--t-end", "0.0005", "--output-every", "0.002", "--out",
                                                    (dir.path() / "never").string()}, dir.path());
  EXPECT_EQ(given.exit_code, 2);
  EXPECT_EQ(given.err, "water_drop: --output-every: must not exceed --t-end\n");
  const Finished ot = run(binary("orszag_tang"), {"--t-end", "0.002", "--nx", "16", "--variant", "none", "--no-render",
                                                  "--threads", "1", "--out", (dir.path() / "ot").string()}, dir.path());
  EXPECT_EQ(ot.exit_code, 0) << ot.err;  // `orszag_tang --t-end 0.01` failed on --output-every before
  EXPECT_TRUE(fs::exists(dir.path() / "ot" / "none" / "view.pvsm"));
}
