// Option fuzz of every example (issue #21): for every option an example's --help lists, every
// hostile value of its type (option_fuzz.hpp) on top of a tiny, short base run, each case with a
// time limit in a folder of its own (its working directory). Asserted for every case: no crash,
// no hang, exit 0 (ran), 2 (rejected with one line, and nothing written: the folder holds only
// what it held before), 3 (failed cleanly) or, for a legitimately long run, gone within a second
// of the SIGTERM sent at the limit. SPHARK_FUZZ_TABLE=<file> writes the table (what was typed,
// what happens now) as Markdown: docs/robustness.md holds it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>

#include "option_fuzz.hpp"
#include "../support/temp_dir.hpp"

using namespace sphark;
using namespace sphark::test;
namespace fs = std::filesystem;

namespace {


struct Program {
  std::string name;
  std::vector<std::string> base;
  bool handles_signals;
};

const std::vector<Program>& programs() {
  static const std::vector<Program> p = {
      {"water_drop", {"--spacing", "0.25", "--t-end", "2e-4", "--cleaning", "on", "--no-render", "--threads", "1"}, true},
      {"cleaning_disc",
       {"--spacing", "0.25", "--t-end", "0.05", "--variant", "constrained_sigma0", "--no-render", "--threads", "1"}, true},
      {"orszag_tang", {"--nx", "8", "--t-end", "0.01", "--variant", "cleaning", "--no-render", "--threads", "1"}, true},
      {"cylinder_lattice", {"--case", "single", "--particles", "40", "--t-end", "0.01", "--no-render", "--threads", "1"}, true},
      {"stepper_study",
       {"--scene", "drop", "--what", "matrix", "--methods", "BOGACKI_SHAMPINE_4_2_3", "--modes", "capped", "--rtols", "1e-3",
        "--fixed-methods", "none", "--leapfrog-methods", "none", "--t-end", "0.0005", "--outputs", "1", "--spacing", "0.25",
        "--reference-rtol", "1e-6", "--no-render", "--threads", "1"},
       true},
      {"gravitating_sphere", {"--particles", "100", "--t-end", "0.01", "--no-render", "--threads", "1"}, true},
      {"cloud_collapse", {"--particles", "1000", "--t-end", "0.001", "--output-every", "0", "--no-render", "--threads", "1"}, true},
      {"ghost_static", {"--only", "fig5", "--particles", "2000", "--cost-particles", "1000", "--draws", "2", "--no-plots"}, false},
      {"second_derivative_1d", {"--levels", "2", "--no-plots", "--no-timing"}, false}};
  return p;
}

// Every option x every hostile value of its type, flags given a value and given alone, and
// mistyped option names.
std::vector<FuzzCase> generate(const Program& p, const TempDir& dir) {
  const Finished help = run(require_example(p.name), {"--help"}, dir.path());
  EXPECT_EQ(help.exit_code, 0) << p.name;
  const std::vector<HelpOption> options = parse_help(help.out);
  EXPECT_GE(options.size(), 5u) << p.name << ": " << help.out;
  std::vector<FuzzCase> cases;
  const auto add = [&](std::vector<std::string> typed) { cases.push_back({p.name, p.base, std::move(typed), p.handles_signals}); };
  for (const HelpOption& o : options) {
    if (o.metavar.empty()) {
      add({o.name});
      add({o.name + "=1"});
      continue;
    }
    for (const std::string& v : hostile_values(o.metavar)) add({o.name, v});
  }
  for (const char* typo : {"--t_end", "--T-END", "-t", "t-end", "--"}) add({typo, "1"});
  return cases;
}

std::string cell(std::string s) {  // a Markdown table cell
  for (char& ch : s)
    if (ch == '|' || ch == '\n') ch = '/';
  return s;
}

void write_table(const std::vector<FuzzOutcome>& all, const char* file) {
  std::ofstream t(file);
  t << "| program | typed (on top of the base run) | exit | what happens now |\n|---|---|---|---|\n";
  for (const FuzzOutcome& o : all) {
    const std::string code = o.r.term_signal ? "signal " + std::to_string(o.r.term_signal) : std::to_string(o.r.f.exit_code);
    t << "| " << o.c.program << " | `" << cell(joined(o.c.typed)) << "` | " << code << " | " << cell(o.what) << " |\n";
  }
}

}  // namespace

TEST(OptionFuzz, EveryOptionOfEveryExampleSurvivesHostileValues) {
  TempDir dir;
  std::vector<FuzzCase> cases;
  for (const Program& p : programs()) {
    const std::vector<FuzzCase> c = generate(p, dir);
    cases.insert(cases.end(), c.begin(), c.end());
  }
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<FuzzOutcome> all = run_all(cases, dir.path());
  std::map<std::string, int> by_exit;
  int failures = 0;
  for (const FuzzOutcome& o : all) {
    ++by_exit[o.r.stopped ? "stopped at the limit" : o.r.term_signal ? "signal" : "exit " + std::to_string(o.r.f.exit_code)];
    if (o.verdict.empty()) continue;
    ++failures;
    ADD_FAILURE() << o.c.program << " " << joined(o.c.typed) << ": " << o.verdict << "\n" << o.r.f.err.substr(0, 2000);
  }
  std::printf("%zu cases in %.1f s:", all.size(), seconds_since(t0));
  for (const auto& [k, n] : by_exit) std::printf("  %s: %d", k.c_str(), n);
  std::printf("\n");
  EXPECT_EQ(failures, 0);
  if (const char* file = std::getenv("SPHARK_FUZZ_TABLE")) write_table(all, file);
}
