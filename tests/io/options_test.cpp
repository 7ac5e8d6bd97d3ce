// Command-line options: typed parsing, and for every class of bad input exactly one line
// "<program>: <option>: <reason>" on stderr plus the usage-error status (exit code 2).
#include <gtest/gtest.h>

#include <cmath>
#include <cctype>
#include <fstream>
#include <sstream>

#include "sphark/cli/options.hpp"
#include "sphark/integrate/stepper.hpp"
#include "../support/temp_dir.hpp"

namespace sphark {
namespace {

const std::vector<std::string> kSteppers = {"ARKODE_HEUN_EULER_2_1_2",
                                           "ARKODE_DORMAND_PRINCE_7_4_5", "ark-imex", "leapfrog"};

struct Parsed {
  ParseStatus status;
  std::string out, err;
};

// Parses `args` (without the program name) into `o` with the core options plus extras.
Parsed run(std::vector<std::string> args, CoreOptions& o, long* seed = nullptr,
           std::string* kernel = nullptr, bool* cleaning = nullptr, Real* alpha = nullptr) {
  OptionParser p("water_drop", "2D water drop");
  add_core_options(p, o, kSteppers);
  if (seed) p.add("--seed", seed, "random seed", Range{0, 1000});
  if (kernel) p.add("--kernel", kernel, "SPH kernel", OneOf{{"cubic", "wendland-c2"}});
  if (cleaning) p.add_switch("--cleaning", cleaning, "divergence cleaning");
  if (alpha) p.add("--alpha", alpha, "viscosity");
  args.insert(args.begin(), "water_drop");
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  const ParseStatus s = p.parse(static_cast<int>(argv.size()), argv.data());
  Parsed r{s, ::testing::internal::GetCapturedStdout(), ::testing::internal::GetCapturedStderr()};
  return r;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string l; std::getline(ss, l);) out.push_back(l);
  return out;
}

// Runs of whitespace (including the help text's line wraps) -> one space.
std::string collapse_space(const std::string& text) {
  std::string out;
  for (char c : text) {
    const bool space = std::isspace(static_cast<unsigned char>(c));
    if (!space || out.empty() || out.back() != ' ') out += space ? ' ' : c;
  }
  return out;
}

void expect_usage_error(std::vector<std::string> args, const std::string& line) {
  CoreOptions o;
  long seed = 0;
  std::string kernel = "cubic";
  bool cleaning = true;
  Real alpha = 1;
  const Parsed r = run(std::move(args), o, &seed, &kernel, &cleaning, &alpha);
  EXPECT_EQ(r.status, ParseStatus::usage_error);
  EXPECT_EQ(r.err, line + "\n");  // exactly one line
  EXPECT_TRUE(r.out.empty());
}

TEST(Options, ParsesEveryType) {
  CoreOptions o;
  long seed = 0;
  std::string kernel = "cubic";
  bool cleaning = true;
  Real alpha = 1;
  const Parsed r = run({"--out", "results/a", "--t-end=0.25", "--stepper", "leapfrog",
                        "--rtol", "1e-8", "--atol=3.5e-12", "--dt", "0", "--output-every",
                        "+0.01", "--threads", "+2", "--no-render", "--seed", "17", "--kernel",
                        "wendland-c2", "--cleaning", "off", "--alpha", "-0.5"},
                       o, &seed, &kernel, &cleaning, &alpha);
  ASSERT_EQ(r.status, ParseStatus::ok) << r.err;
  EXPECT_TRUE(r.err.empty());
  EXPECT_EQ(o.out, std::filesystem::path("results/a"));
  EXPECT_EQ(o.t_end, 0.25);
  EXPECT_EQ(o.stepper, "leapfrog");
  EXPECT_EQ(o.rtol, 1e-8);
  EXPECT_EQ(o.atol, 3.5e-12);
  EXPECT_EQ(o.dt, 0.0);
  EXPECT_EQ(o.output_every, 0.01);
  EXPECT_EQ(o.threads, 2);
  EXPECT_FALSE(o.render);
  EXPECT_EQ(seed, 17);
  EXPECT_EQ(kernel, "wendland-c2");
  EXPECT_FALSE(cleaning);
  EXPECT_EQ(alpha, -0.5);
}

TEST(Options, DefaultsStayWithoutArguments) {
  CoreOptions o;
  const CoreOptions d;
  ASSERT_EQ(run({}, o).status, ParseStatus::ok);
  EXPECT_EQ(o.out, d.out);
  EXPECT_EQ(o.t_end, d.t_end);
  EXPECT_EQ(o.stepper, d.stepper);
  EXPECT_EQ(o.rtol, d.rtol);
  EXPECT_TRUE(o.render);
}

TEST(Options, EachBadInputIsOneLine) {
  expect_usage_error({"--bogus", "1"}, "water_drop: --bogus: unknown option (try --help)");
  expect_usage_error({"stray"}, "water_drop: 'stray': unexpected argument (try --help)");
  expect_usage_error({"--rtol", "abc"},
                     "water_drop: --rtol: bad value 'abc' (expected a positive real number)");
  expect_usage_error({"--rtol", "1e-6x"},
                     "water_drop: --rtol: bad value '1e-6x' (expected a positive real number)");
  expect_usage_error({"--t-end", "-1"},
                     "water_drop: --t-end: bad value '-1' (expected a positive real number)");
  expect_usage_error({"--t-end", "0"},
                     "water_drop: --t-end: bad value '0' (expected a positive real number)");
  expect_usage_error({"--dt=-1e-3"},
                     "water_drop: --dt: bad value '-1e-3' (expected a non-negative real number)");
  expect_usage_error({"--mri-levels", "1"},
                     "water_drop: --mri-levels: bad value '1' (expected an integer in [2, 8])");
  expect_usage_error({"--alpha", "nan"},
                     "water_drop: --alpha: bad value 'nan' (expected a real number)");
  expect_usage_error({"--alpha", "inf"},
                     "water_drop: --alpha: bad value 'inf' (expected a real number)");
  expect_usage_error({"--rtol", "-infinity"},
                     "water_drop: --rtol: bad value '-infinity' (expected a positive real number)");
  expect_usage_error({"--alpha", "1e400"},
                     "water_drop: --alpha: bad value '1e400' (expected a real number)");
  expect_usage_error({"--rtol", "+-1"},
                     "water_drop: --rtol: bad value '+-1' (expected a positive real number)");
  expect_usage_error({"--threads", "1.5"},
                     "water_drop: --threads: bad value '1.5' (expected a non-negative integer)");
  expect_usage_error({"--threads", "99999999999"},
                     "water_drop: --threads: bad value '99999999999' (expected a non-negative integer)");
  expect_usage_error({"--seed", "1001"},
                     "water_drop: --seed: bad value '1001' (expected an integer in [0, 1000])");
  expect_usage_error({"--stepper", "rk4"},
                     "water_drop: --stepper: bad value 'rk4' (expected one of: "
                     "ARKODE_HEUN_EULER_2_1_2, ARKODE_DORMAND_PRINCE_7_4_5, ark-imex, leapfrog)");
  expect_usage_error({"--kernel", ""},
                     "water_drop: --kernel: bad value '' (expected one of: cubic, wendland-c2)");
  expect_usage_error({"--cleaning", "yes"},
                     "water_drop: --cleaning: bad value 'yes' (expected on or off)");
  expect_usage_error({"--t-end"},
                     "water_drop: --t-end: missing value (expected a positive real number)");
  expect_usage_error({"--t-end", "--rtol", "1"},
                     "water_drop: --t-end: missing value (expected a positive real number)");
  expect_usage_error({"--out="}, "water_drop: --out: bad value '' (expected a path)");
  expect_usage_error({"--no-render=1"}, "water_drop: --no-render: takes no value (got '1')");
}

TEST(Options, HelpListsEveryOptionWithDefaultAndMeaning) {
  CoreOptions o;
  o.t_end = 0.1;
  long seed = 5;
  std::string kernel = "cubic";
  bool cleaning = true;
  Real alpha = 1;
  // --help wins even after a bad option.
  const Parsed r = run({"--bogus", "--t-end", "0.5", "--help"}, o, &seed, &kernel, &cleaning,
                       &alpha);
  EXPECT_EQ(r.status, ParseStatus::help);
  EXPECT_TRUE(r.err.empty());
  EXPECT_EQ(r.out.rfind("water_drop: 2D water drop\n", 0), 0u);
  for (const auto& line : lines(r.out)) EXPECT_LE(line.size(), 100u) << line;
  const std::string h = collapse_space(r.out);  // help text is wrapped at 100 columns
  for (const char* piece :
       {"--out DIR ", "(a path; default out)", "--t-end REAL ", "end time (a positive real number; default 0.1)",
        "--stepper NAME ", "(one of: ARKODE_HEUN_EULER_2_1_2, ARKODE_DORMAND_PRINCE_7_4_5, ark-imex, leapfrog; "
        "default ARKODE_DORMAND_PRINCE_7_4_5)",
        "--rtol REAL ", "default 1e-06", "--atol REAL ", "default 1e-09", "--dt REAL ",
        "fixed time step, 0 = adaptive (a non-negative real number; default 0)",
        "--output-every REAL ", "--threads INT ", "(a non-negative integer; default 0)",
        "--no-render ", "do not render pictures at the end", "--seed INT ",
        "(an integer in [0, 1000]; default 5)", "--kernel NAME ", "--cleaning on|off ",
        "(on or off; default on)", "--alpha REAL ", "--help ", "print this help and exit"}) {
    EXPECT_NE(h.find(piece), std::string::npos) << "missing: " << piece << "\n" << h;
  }
}

TEST(Options, CommaSeparatedLists) {
  std::vector<Real> widths = {0.5, 1};
  std::vector<int> resolutions = {25, 50};
  auto parse = [&](std::vector<const char*> argv) {
    OptionParser p("conv", "convergence study");
    p.add("--widths", &widths, "kernel widths", Positive{});
    p.add("--n", &resolutions, "resolutions", Range{2, 4096});
    argv.insert(argv.begin(), "conv");
    ::testing::internal::CaptureStderr();
    const ParseStatus s = p.parse(static_cast<int>(argv.size()), argv.data());
    return std::pair{s, ::testing::internal::GetCapturedStderr()};
  };
  auto [ok, err] = parse({"--widths", "1.2,1.5,2", "--n=25,50,100,200"});
  EXPECT_EQ(ok, ParseStatus::ok) << err;
  EXPECT_EQ(widths, (std::vector<Real>{1.2, 1.5, 2}));
  EXPECT_EQ(resolutions, (std::vector<int>{25, 50, 100, 200}));
  EXPECT_EQ(parse({"--widths", "1,-2"}).second,
            "conv: --widths: bad value '1,-2' (expected a comma-separated list of positive real "
            "numbers)\n");
  EXPECT_EQ(parse({"--widths", "1,,2"}).first, ParseStatus::usage_error);
  EXPECT_EQ(parse({"--widths", "1,nan"}).first, ParseStatus::usage_error);
  EXPECT_EQ(parse({"--n", "25,1"}).second,
            "conv: --n: bad value '25,1' (expected a comma-separated list of integers in "
            "[2, 4096])\n");
  EXPECT_EQ(widths, (std::vector<Real>{1.2, 1.5, 2}));  // failed parses assign nothing
}

TEST(CoreOptions, StepperNamesAndMapping) {
  const auto names = core_stepper_names();
  const auto erk = erk_table_names();
  const auto mri = mri_table_names();
  ASSERT_EQ(names.size(), erk.size() + 4 + mri.size());
  EXPECT_TRUE(std::equal(erk.begin(), erk.end(), names.begin()));
  EXPECT_EQ(names[erk.size()], "ark-imex");
  EXPECT_EQ(names[erk.size() + 1], "leapfrog");
  EXPECT_EQ(names[erk.size() + 2], "leapfrog-rev");
  EXPECT_EQ(names[erk.size() + 3], "leapfrog-blocks");
  for (std::size_t i = 0; i < mri.size(); ++i) EXPECT_EQ(names[erk.size() + 4 + i], "mri-" + mri[i]);
  // The default --stepper is StepperOptions' default method, and a valid name.
  CoreOptions o;
  EXPECT_EQ(o.stepper, StepperOptions{}.method);
  OptionParser p("x", "y");
  EXPECT_NO_THROW(add_core_options(p, o));
  const char* argv[] = {"x", "--stepper", "leapfrog", "--rtol", "1e-8", "--atol", "1e-12",
                        "--dt", "0.001"};
  ASSERT_EQ(p.parse(9, argv), ParseStatus::ok);
  const StepperOptions s = stepper_options(o);
  EXPECT_EQ(s.method, "leapfrog");
  EXPECT_EQ(s.rtol, 1e-8);
  EXPECT_EQ(s.atol, std::vector<Real>{1e-12});
  EXPECT_EQ(s.fixed_dt, 0.001);
  const char* mri_argv[] = {"x", "--stepper", "mri-ARKODE_MRI_GARK_ERK45a", "--mri-ratio", "16",
                            "--mri-fast-table", "ARKODE_DORMAND_PRINCE_7_4_5", "--max-dt", "0.5",
                            "--partition-hysteresis", "0.125", "--mri-levels", "3"};
  EXPECT_EQ(s.partition_hysteresis, StepperOptions{}.partition_hysteresis);  // the default passed on
  EXPECT_EQ(s.mri_levels, 2);
  ASSERT_EQ(p.parse(13, mri_argv), ParseStatus::ok);
  const StepperOptions m = stepper_options(o);
  EXPECT_EQ(m.partition_hysteresis, 0.125);
  EXPECT_EQ(m.method, "mri-ARKODE_MRI_GARK_ERK45a");
  EXPECT_EQ(m.mri_ratio, 16);
  EXPECT_EQ(m.mri_levels, 3);
  EXPECT_EQ(m.mri_fast_table, "ARKODE_DORMAND_PRINCE_7_4_5");
  EXPECT_EQ(m.max_dt, 0.5);
}

namespace {
class TwoEntries : public OdeSystem {
 public:
  std::size_t size() const override { return 2; }
  int rhs(Real, const Real*, Real* ydot) override { return ydot[0] = ydot[1] = 0, 0; }
};
}  // namespace

// --velocity-tolerance belongs to the leapfrogs (leapfrog, leapfrog-blocks); with another
// stepper it is dropped, said in one line (a scene that defaults to it, the cloud collapse, runs
// ARKODE's steppers too).
TEST(Options, AVelocityToleranceWithAnotherStepperIsDroppedWithALine) {
  TwoEntries sys;
  CoreOptions o;
  o.velocity_tolerance = 0.1;
  for (const char* leapfrog : {"leapfrog", "leapfrog-blocks"}) {
    o.stepper = leapfrog;
    EXPECT_EQ(stepper_options(o, sys, "prog").velocity_tolerance, 0.1) << leapfrog;
  }
  o.stepper = "ARKODE_BOGACKI_SHAMPINE_4_2_3";
  ::testing::internal::CaptureStderr();
  const StepperOptions s = stepper_options(o, sys, "prog");
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(s.velocity_tolerance, 0);
  EXPECT_EQ(err, "prog: --velocity-tolerance 0.1 applies to --stepper leapfrog and leapfrog-blocks only; "
                 "ARKODE_BOGACKI_SHAMPINE_4_2_3 does not iterate its corrector\n");
}

TEST(Options, ProgrammerErrorsThrow) {
  OptionParser p("x", "y");
  Real bad = -1, good = 1;
  EXPECT_THROW(p.add("--a", &bad, "", Positive{}), std::logic_error);
  p.add("--b", &good, "");
  EXPECT_THROW(p.add("--b", &good, ""), std::logic_error);
  EXPECT_THROW(p.add("b", &good, ""), std::logic_error);
  EXPECT_THROW(p.add("--help", &good, ""), std::logic_error);
  std::string s = "x";
  EXPECT_THROW(p.add("--s", &s, "", OneOf{{"a", "b"}}), std::logic_error);
}

TEST(OptionsDeathTest, ParseOrExitCodes) {
  auto parse = [](std::vector<const char*> argv) {
    CoreOptions o;
    OptionParser p("water_drop", "2D water drop");
    add_core_options(p, o, kSteppers);
    p.parse_or_exit(static_cast<int>(argv.size()), argv.data());
    std::exit(7);  // parsed fine
  };
  EXPECT_EXIT(parse({"water_drop", "--rtol", "abc"}), ::testing::ExitedWithCode(2),
              "^water_drop: --rtol: bad value 'abc' \\(expected a positive real number\\)\n$");
  EXPECT_EXIT(parse({"water_drop", "--help"}), ::testing::ExitedWithCode(0), "^$");
  EXPECT_EXIT(parse({"water_drop", "--t-end", "2"}), ::testing::ExitedWithCode(7), "");
  EXPECT_EXIT(exit_usage_error("water_drop", "--t-end", "must exceed --output-every"),
              ::testing::ExitedWithCode(2), "^water_drop: --t-end: must exceed --output-every\n$");
}

TEST(OutputDir, CreatesParentsAndChecksWritability) {
  test::TempDir dir;
  const auto nested = dir.path() / "a" / "b" / "c";
  EXPECT_EQ(output_dir_problem(nested), std::nullopt);
  EXPECT_TRUE(std::filesystem::is_directory(nested));
  EXPECT_TRUE(std::filesystem::is_empty(nested));  // the write probe is removed
  std::ofstream(dir.path() / "file") << "x";
  const auto problem = output_dir_problem(dir.path() / "file" / "sub");
  ASSERT_TRUE(problem.has_value());
  EXPECT_NE(problem->find("cannot create"), std::string::npos) << *problem;
  EXPECT_TRUE(output_dir_problem(dir.path() / "file").has_value());
  EXPECT_EXIT(prepare_output_dir(dir.path() / "file" / "sub", "water_drop"),
              ::testing::ExitedWithCode(2), "^water_drop: --out: cannot create '.*/file/sub': .*\n$");
}

}  // namespace
}  // namespace sphark
