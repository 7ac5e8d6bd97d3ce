// Reproduces seed 001 (SPH second derivatives near boundaries in 1D): Tables 1-5 as CSV + Markdown,
// the data and PNGs of Figures 2, 4, 5, a second test function and the cost of each operator.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

#include "scene.hpp"
#include "sphark/cli/options.hpp"
#include "sphark/core/profile.hpp"

using namespace sphark::d1;

namespace {

// Options: one line naming the option, the bad value and what is allowed, exit code 2, and no
// file written (the output directory is checked before any work).
scene::Options parse(int argc, char** argv) {
  scene::Options o;
  long seed = static_cast<long>(o.seed);
  sphark::OptionParser p("second_derivative_1d",
                         "Reproduces seed 001, Tables 1-5 and Figures 2, 4, 5 (CSPM, BIM, ICSPM second derivatives in 1D)");
  p.add("--out", &o.out, "output folder", "DIR");
  p.add("--seed", &seed, "random particle set for Tables 4-5 and Figures 4-5", sphark::NonNegative{});
  p.add("--seeds", &o.seeds, "also repeat Tables 4-5 over K random sets S..S+K-1: mean and spread of e_N",
        sphark::Range{1, 10000});
  p.add("--levels", &o.levels, "N = 11, 21, ..., 10*2^(L-1)+1 (8: up to 1281)", sphark::Range{2, 10});
  p.add_flag("--no-plots", &o.plots, "do not call vis/second_derivative_1d.py", false);
  p.add_flag("--no-timing", &o.timing, "skip the cost measurements (timing.csv)", false);
  p.add_flag("--profile", &o.profile, "print the wall-time split (output: the CSV writes; the rest: computing)");
  p.parse_or_exit(argc, argv);
  o.seed = static_cast<std::uint64_t>(seed);
  sphark::prepare_output_dir(o.out, p.program());
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
  sphark::run_profile().enable(opt.profile);
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
  if (opt.profile) sphark::run_profile().print(std::cout, elapsed);
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
