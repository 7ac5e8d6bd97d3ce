// OptionParser and JSON (cli/options.hpp): every option's value serialised with its name and
// type; --config applies a run record's or a flat object's values through the same checks as
// the command line, the command line overriding them wherever it stands; a bad entry is one
// line naming the option and the usage-error status; was_given tells a user's value from a
// default, and a default interval follows a short run (issue #21).
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include "sphark/cli/options.hpp"
#include "../support/temp_dir.hpp"

namespace sphark {
namespace {

struct Values {
  CoreOptions core;
  long seed = 7;
  std::string kernel = "cubic";
  bool cleaning = true;
  std::vector<Real> resolutions = {25, 50};
  std::vector<int> counts;
  std::filesystem::path restart;
};

struct Parsed {
  ParseStatus status;
  std::string err;
  std::vector<OptionRecord> records;
  Json json;
  std::vector<bool> given;  // was_given of --t-end, --rtol, --seed, --no-render
};

Parsed parse(Values& v, std::vector<std::string> args) {
  OptionParser p("water_drop", "test");
  add_core_options(p, v.core, {"ARKODE_HEUN_EULER_2_1_2", "ARKODE_DORMAND_PRINCE_7_4_5", "leapfrog"});
  p.add("--seed", &v.seed, "seed", Range{0, 1000});
  p.add("--kernel", &v.kernel, "kernel", OneOf{{"cubic", "wendland-c2"}});
  p.add_switch("--cleaning", &v.cleaning, "cleaning");
  p.add("--resolutions", &v.resolutions, "resolutions", Positive{});
  p.add("--counts", &v.counts, "counts", NonNegative{});
  p.add("--restart", &v.restart, "checkpoint", "FILE");
  args.insert(args.begin(), "water_drop");
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  ::testing::internal::CaptureStderr();
  const ParseStatus s = p.parse(static_cast<int>(argv.size()), argv.data());
  Parsed r{s, ::testing::internal::GetCapturedStderr(), p.records(), p.to_json(), {}};
  for (const char* n : {"--t-end", "--rtol", "--seed", "--no-render"}) r.given.push_back(p.was_given(n));
  return r;
}

std::filesystem::path write(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file) << text;
  return file;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST(OptionRecords, EveryOptionWithNameTypeValueAndWhetherGiven) {
  Values v;
  const Parsed r = parse(v, {"--t-end", "0.25", "--no-render", "--counts", "1,2"});
  ASSERT_EQ(r.status, ParseStatus::ok) << r.err;
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"out", "path"},         {"t-end", "real"},       {"stepper", "string"},    {"rtol", "real"},
      {"atol", "real"},        {"dt", "real"},          {"step-cap", "switch"},   {"max-dt", "real"},
      {"velocity-tolerance", "real"},
      {"mri-ratio", "integer"}, {"mri-levels", "integer"}, {"mri-fast-table", "string"}, {"partition-hysteresis", "real"}, {"block-cycles", "string"},
      {"output-every", "real"},
      {"threads", "integer"},
      {"no-render", "flag"},   {"profile", "flag"},     {"seed", "integer"},      {"kernel", "string"},
      {"cleaning", "switch"},  {"resolutions", "real list"}, {"counts", "integer list"}, {"restart", "path"}};
  ASSERT_EQ(r.records.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(r.records[i].name, expected[i].first);
    EXPECT_EQ(r.records[i].type, expected[i].second) << expected[i].first;
    EXPECT_TRUE(r.records[i].value == *r.json.find(expected[i].first)) << expected[i].first;
    const bool given = expected[i].first == "t-end" || expected[i].first == "no-render" || expected[i].first == "counts";
    EXPECT_EQ(r.records[i].given, given) << expected[i].first;
  }
  EXPECT_EQ(to_json_line(r.json),
            "{\"out\": \"out\", \"t-end\": 0.25, \"stepper\": \"ARKODE_DORMAND_PRINCE_7_4_5\", \"rtol\": 1e-06, "
            "\"atol\": 1e-09, \"dt\": 0, \"step-cap\": true, \"max-dt\": 0, \"velocity-tolerance\": 0, \"mri-ratio\": 4, \"mri-levels\": 2, "
            "\"mri-fast-table\": \"ARKODE_ZONNEVELD_5_3_4\", \"partition-hysteresis\": 0.25, \"block-cycles\": \"fixed\", \"output-every\": 0, \"threads\": 0, \"no-render\": true, \"profile\": false, "
            "\"seed\": 7, \"kernel\": \"cubic\", \"cleaning\": true, \"resolutions\": [25, 50], \"counts\": [1, 2], "
            "\"restart\": \"\"}");
  EXPECT_EQ(r.given, (std::vector<bool>{true, false, false, true}));
}

TEST(OptionConfig, ARecordReadBackGivesBitIdenticalValues) {
  test::TempDir dir;
  Values a;
  const Parsed first = parse(a, {"--t-end", "0.1", "--rtol", "3.3e-7", "--resolutions", "0.1,0.7,1e-300",
                                 "--cleaning", "off", "--seed", "999", "--out", "dir with \"quotes\""});
  ASSERT_EQ(first.status, ParseStatus::ok) << first.err;
  Json record = Json::Object{};
  record["program"] = "water_drop";
  record["options"] = first.json;
  const auto file = write(dir.path() / "run.json", to_json_text(record));
  Values b;
  b.core.t_end = 5;  // other defaults: the config must set every one
  b.resolutions = {};
  const Parsed again = parse(b, {"--config", file.string()});
  ASSERT_EQ(again.status, ParseStatus::ok) << again.err;
  EXPECT_TRUE(same_bits(b.core.t_end, a.core.t_end));
  EXPECT_TRUE(same_bits(b.core.rtol, a.core.rtol));
  ASSERT_EQ(b.resolutions.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(same_bits(b.resolutions[i], a.resolutions[i]));
  EXPECT_EQ(b.resolutions[2], 1e-300);
  EXPECT_FALSE(b.cleaning);
  EXPECT_EQ(b.seed, 999);
  EXPECT_EQ(b.core.out, "dir with \"quotes\"");
  EXPECT_TRUE(again.json == first.json);
  for (const auto& r : again.records) EXPECT_TRUE(r.given) << r.name;  // a config's values count as given
}

TEST(OptionConfig, TheCommandLineOverridesTheConfigWhereverItStands) {
  test::TempDir dir;
  const auto file = write(dir.path() / "c.json", R"({"t-end": 0.5, "rtol": 1e-3, "seed": 3, "no-render": true})");
  for (const bool config_first : {true, false}) {
    Values v;
    const std::vector<std::string> cfg = {"--config", file.string()}, cli = {"--t-end", "0.2", "--seed=4"};
    std::vector<std::string> args = config_first ? cfg : cli;
    args.insert(args.end(), (config_first ? cli : cfg).begin(), (config_first ? cli : cfg).end());
    const Parsed r = parse(v, args);
    ASSERT_EQ(r.status, ParseStatus::ok) << r.err;
    EXPECT_EQ(v.core.t_end, 0.2);  // command line
    EXPECT_EQ(v.seed, 4);          // command line
    EXPECT_EQ(v.core.rtol, 1e-3);  // config
    EXPECT_FALSE(v.core.render);   // config
    EXPECT_EQ(v.core.atol, 1e-9);  // default
    EXPECT_EQ(r.given, (std::vector<bool>{true, true, true, true}));
  }
  // two configs: applied in order, the later wins
  const auto second = write(dir.path() / "d.json", R"({"rtol": 1e-5, "no-render": false})");
  Values v;
  ASSERT_EQ(parse(v, {"--config", file.string(), "--config=" + second.string()}).status, ParseStatus::ok);
  EXPECT_EQ(v.core.rtol, 1e-5);
  EXPECT_TRUE(v.core.render);  // a flag's false in a config: as if not given on the command line
  EXPECT_EQ(v.core.t_end, 0.5);
}

TEST(OptionConfig, EachBadEntryIsOneLineNamingTheOption) {
  test::TempDir dir;
  const std::string f = (dir.path() / "c.json").string();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"t-end": -1})", "water_drop: --t-end: bad value '-1' in config '" + f + "' (expected a positive real number)"},
      {R"({"t-end": "0.1"})", "water_drop: --t-end: bad value '\"0.1\"' in config '" + f + "' (expected a positive real number)"},
      {R"({"seed": 1001})", "water_drop: --seed: bad value '1001' in config '" + f + "' (expected an integer in [0, 1000])"},
      {R"({"seed": 2.5})", "water_drop: --seed: bad value '2.5' in config '" + f + "' (expected an integer in [0, 1000])"},
      {R"({"kernel": "gauss"})", "water_drop: --kernel: bad value '\"gauss\"' in config '" + f + "' (expected one of: cubic, wendland-c2)"},
      {R"({"cleaning": 1})", "water_drop: --cleaning: bad value '1' in config '" + f + "' (expected true or false)"},
      {R"({"no-render": "yes"})", "water_drop: --no-render: bad value '\"yes\"' in config '" + f + "' (expected true or false)"},
      {R"({"resolutions": [1, -2]})", "water_drop: --resolutions: bad value '[1, -2]' in config '" + f + "' (expected a comma-separated list of positive real numbers)"},
      {R"({"resolutions": []})", "water_drop: --resolutions: bad value '[]' in config '" + f + "' (expected a comma-separated list of positive real numbers)"},
      {R"({"rtol": null})", "water_drop: --rtol: bad value 'null' in config '" + f + "' (expected a positive real number)"},
      {R"({"t_end": 1})", "water_drop: --t_end: unknown option in config '" + f + "' (try --help)"},
      {R"({"options": {"nx": 64}, "program": "water_drop"})", "water_drop: --nx: unknown option in config '" + f + "' (try --help)"},
      {R"({"options": {}, "program": "orszag_tang"})", "water_drop: --config: '" + f + "' records a run of orszag_tang, not water_drop"},
      {R"([1, 2])", "water_drop: --config: '" + f + "' is not a JSON object"},
      {R"({"t-end": 1,})", "water_drop: --config: '" + f + "': line 1, column 13: expected a key (a string in double quotes)"},
  };
  for (const auto& [text, line] : cases) {
    write(f, text);
    Values v;
    const Parsed r = parse(v, {"--t-end", "0.3", "--config", f});
    EXPECT_EQ(r.status, ParseStatus::usage_error) << text;
    EXPECT_EQ(r.err, line + "\n") << text;
  }
  Values v;
  Parsed r = parse(v, {"--config", (dir.path() / "missing.json").string()});
  EXPECT_EQ(r.err, "water_drop: --config: cannot read '" + (dir.path() / "missing.json").string() + "': no such file\n");
  r = parse(v, {"--config"});
  EXPECT_EQ(r.err, "water_drop: --config: missing value (expected a JSON FILE, e.g. a run.json)\n");
}

TEST(OptionConfig, ARecordsDefaultsAreAcceptedAsTheyStand) {
  // "restart": "" and "counts": [] cannot be typed on the command line, but they are the defaults
  // a run record stores: reading them back changes nothing
  test::TempDir dir;
  Values v;
  const auto file = write(dir.path() / "c.json", R"({"restart": "", "counts": [], "out": "o"})");
  const Parsed r = parse(v, {"--config", file.string()});
  ASSERT_EQ(r.status, ParseStatus::ok) << r.err;
  EXPECT_TRUE(v.restart.empty());
  EXPECT_TRUE(v.counts.empty());
  EXPECT_EQ(v.core.out, "o");
}

TEST(OptionConfigDeathTest, ADefaultIntervalFollowsAShortRunAGivenOneIsAnError) {
  OptionParser p("orszag_tang", "test");
  Values w;
  w.core.output_every = 0.05;  // a program's default, longer than the run below
  add_core_options(p, w.core);
  const char* short_run[] = {"orszag_tang", "--t-end", "0.01"};
  ASSERT_EQ(p.parse(3, short_run), ParseStatus::ok);
  limit_to_t_end(p, "--output-every", w.core.output_every, w.core.t_end);
  EXPECT_EQ(w.core.output_every, 0.01);  // followed the run
  Values x;
  x.core.output_every = 0.05;
  OptionParser q("orszag_tang", "test");
  add_core_options(q, x.core);
  const char* given[] = {"orszag_tang", "--t-end", "0.01", "--output-every", "0.05"};
  ASSERT_EQ(q.parse(5, given), ParseStatus::ok);
  EXPECT_EXIT(limit_to_t_end(q, "--output-every", x.core.output_every, x.core.t_end), ::testing::ExitedWithCode(2),
              "orszag_tang: --output-every: must not exceed --t-end");
  EXPECT_THROW((void)q.was_given("--no-such-option"), std::logic_error);
}

TEST(OptionConfig, HelpMentionsConfig) {
  OptionParser p("water_drop", "test");
  Real t = 1;
  p.add("--t-end", &t, "end time", Positive{});
  EXPECT_NE(p.help().find("--config FILE"), std::string::npos);
  EXPECT_THROW(p.add("--config", &t, "clash"), std::logic_error);
}

}  // namespace sphark
