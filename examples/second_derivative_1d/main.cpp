// Reproduces seed 001 (SPH second derivatives near boundaries in 1D): Tables 1-5 as CSV + Markdown,
// the data and PNGs of Figures 2, 4, 5, a second test function and the cost of each operator.
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "scene.hpp"

using namespace sphark::d1;

namespace {

const char* kUsage =
    "usage: second_derivative_1d [--out DIR] [--seed S] [--seeds K] [--levels L] [--no-plots] [--no-timing]\n"
    "  Reproduces seed 001, Tables 1-5 and Figures 2, 4, 5 (CSPM, BIM, ICSPM second derivatives in 1D).\n"
    "  --out DIR    output folder (default out/second_derivative_1d)\n"
    "  --seed S     random particle set for Tables 4-5 and Figures 4-5 (default 1)\n"
    "  --seeds K    also repeat Tables 4-5 over K random sets S..S+K-1: mean and spread of e_N (default 1)\n"
    "  --levels L   N = 11, 21, ..., 10*2^(L-1)+1 (default 8: up to 1281; 2..10)\n"
    "  --no-plots   do not call vis/second_derivative_1d.py\n"
    "  --no-timing  skip the cost measurements (timing.csv)\n";

[[noreturn]] void bad(const std::string& option, const std::string& value, const char* why) {
  std::fprintf(stderr, "second_derivative_1d: invalid value '%s' for %s: %s\n", value.c_str(), option.c_str(), why);
  std::exit(2);
}

long long parse_int(const std::string& option, const char* text, long long lo, long long hi) {
  if (text == nullptr) bad(option, "", "missing value");
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(text, &end, 10);
  if (end == text || *end != '\0' || errno != 0) bad(option, text, "not an integer");
  if (v < lo || v > hi) bad(option, text, ("must be in " + std::to_string(lo) + ".." + std::to_string(hi)).c_str());
  return v;
}

scene::Options parse(int argc, char** argv) {
  scene::Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const char* next = i + 1 < argc ? argv[i + 1] : nullptr;
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    } else if (a == "--out") {
      if (next == nullptr || std::string(next).empty()) bad(a, "", "missing directory");
      o.out = next, ++i;
    } else if (a == "--seed") {
      o.seed = static_cast<std::uint64_t>(parse_int(a, next, 0, 1LL << 62)), ++i;
    } else if (a == "--seeds") {
      o.seeds = static_cast<int>(parse_int(a, next, 1, 10000)), ++i;
    } else if (a == "--levels") {
      o.levels = static_cast<int>(parse_int(a, next, 2, 10)), ++i;
    } else if (a == "--no-plots") {
      o.plots = false;
    } else if (a == "--no-timing") {
      o.timing = false;
    } else {
      std::fprintf(stderr, "second_derivative_1d: unknown option '%s' (try --help)\n", a.c_str());
      std::exit(2);
    }
  }
  return o;
}

const char* kTitles[] = {
    "",
    "Table 1: direct f'', uniform particles, c = 2",
    "Table 2: direct f'', uniform particles, BIM with h = k^2 dx",
    "Table 3: boundary-value problem (5.18), uniform particles (CSPM/ICSPM c = 2, BIM h = k^2 dx)",
    "Table 4: direct f'', random particles (CSPM/ICSPM c = 2, BIM h = k^2 max|Omega|)",
    "Table 5: boundary-value problem (5.18), random particles (CSPM/ICSPM c = 2, BIM h = k^2 max|Omega|)"};

}  // namespace

int main(int argc, char** argv) {
  const scene::Options opt = parse(argc, argv);
  const auto t0 = std::chrono::steady_clock::now();
  try {
    std::filesystem::create_directories(opt.out);
    const std::vector<sphark::Index> sizes = paper_sizes(opt.levels);
    std::printf("# seed 001 reproduction: f = x^2 + cos(pi x) on [0, 1]; random tables use --seed %llu\n",
                static_cast<unsigned long long>(opt.seed));
    for (int t = 1; t <= 5; ++t) {
      const auto rows = compute_table(paper_table(t), sizes, opt.seed, seed_function());
      scene::write_table_csv(opt.out / ("table" + std::to_string(t) + ".csv"), rows);
      scene::print_table_markdown(kTitles[t], rows);
    }
    if (opt.seeds > 1)
      for (int t : {4, 5}) scene::seed_statistics(t, opt, sizes);
    // beyond the paper: f = e^x sin(3x) with the Table 1 and Table 3 set-ups
    for (int t : {1, 3}) {
      const auto rows = compute_table(paper_table(t), sizes, opt.seed, exp_sin_function());
      scene::write_table_csv(opt.out / ("table" + std::to_string(t) + "_expsin.csv"), rows);
      scene::print_table_markdown(std::string(kTitles[t]) + " -- second test function f = e^x sin(3x)", rows);
    }
    scene::write_figure_data(opt);
    if (opt.timing) scene::write_timing(opt, sizes);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "second_derivative_1d: %s\n", e.what());
    return 1;
  }
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("\nCSV files in %s (computed in %.1f s)\n", opt.out.c_str(), elapsed);
  if (opt.plots) {
    const std::string script = std::string(SPHARK_SOURCE_DIR) + "/vis/second_derivative_1d.py";
    if (std::system("/usr/bin/python3 -c 'import matplotlib' >/dev/null 2>&1") != 0) {
      std::printf("python3/matplotlib not found: no PNGs made (the CSV files are complete)\n");
    } else if (std::system(("/usr/bin/python3 '" + script + "' '" + opt.out.string() + "'").c_str()) != 0) {
      std::printf("plotting script %s failed: no PNGs (the CSV files are complete)\n", script.c_str());
    } else {
      std::printf("PNG figures in %s\n", opt.out.c_str());
    }
  }
  return 0;
}
