// Ghost particles at curved walls: static reproduction of seed 004 (Fig. 5, Figs. 6-8, Table 1).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>

#include "ghost_static.hpp"
#include "sphark/cli/options.hpp"
#include "sphark/core/profile.hpp"
#include "sphark/io/visualise.hpp"

int main(int argc, char** argv) {
  // Options: one line naming the option, the bad value and what is allowed, exit code 2, and
  // nothing written (the output directory is checked after every option).
  ghost_static::Options opt;
  std::filesystem::path out = opt.out;
  long particles = static_cast<long>(opt.particles), cost_particles = static_cast<long>(opt.cost_particles),
       seed = static_cast<long>(opt.seed);
  std::string only = "all", relax_map = "psi";
  sphark::OptionParser p("ghost_static",
                         "ghost particles at curved walls, static tests of seed 004 (Figs. 5-8, Table 1)");
  p.add("--out", &out, "output directory", "DIR");
  p.add("--particles", &particles, "relaxed inner particles per geometry, Figs. 6-8", sphark::Range{2000, 5000000});
  p.add("--cost-particles", &cost_particles, "random inner particles for Table 1", sphark::Range{1000, 100000000});
  p.add("--draws", &opt.draws, "random draws for Table 1", sphark::Range{2, 1000});
  p.add("--seed", &seed, "random seed", sphark::Range{0, 4294967295.0});
  p.add_flag("--no-plots", &opt.plots, "do not run vis/ghost_static.py at the end", false);
  p.add("--only", &only, "run one part (or all)", sphark::OneOf{{"all", "fig5", "static", "cost"}});
  p.add("--relax-map", &relax_map, "ghosts in the near-wall relaxation", sphark::OneOf{{"psi", "mirror"}});
  bool profile = false;
  p.add_flag("--profile", &profile, "print the wall-time split (output: CSV and VTK writes; the rest: computing)");
  p.parse_or_exit(argc, argv);
  opt.out = out.string();
  opt.particles = static_cast<std::size_t>(particles);
  opt.cost_particles = static_cast<std::size_t>(cost_particles);
  opt.seed = static_cast<unsigned>(seed);
  opt.relax_with_mirror = relax_map == "mirror";
  if (only == "all") only.clear();
  sphark::prepare_output_dir(out, p.program());
  sphark::run_profile().enable(profile);

  const auto t0 = std::chrono::steady_clock::now();
  try {
    if (only.empty() || only == "fig5") ghost_static::write_fig5(opt);
    if (only.empty() || only == "static") ghost_static::run_static(opt);
    if (only.empty() || only == "cost") ghost_static::run_cost_table(opt);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ghost_static: error: %s\n", e.what());
    return 1;
  }
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("total %.1f s\n", total);
  if (profile) sphark::run_profile().print(std::cout, total);

  if (opt.plots) {
    std::printf("/usr/bin/python3 vis/ghost_static.py %s\n", opt.out.c_str());
    std::fflush(stdout);
    if (!sphark::run_python("ghost_static.py", {opt.out}, false)) return 1;  // warning printed
  }
  return 0;
}
