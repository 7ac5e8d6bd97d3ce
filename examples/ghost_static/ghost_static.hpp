#pragma once
// examples/ghost_static: seed 004 §5-7 (Fig. 5, Figs. 6-8, Table 1). Shared declarations.
#include <cstddef>
#include <string>

namespace ghost_static {

struct Options {
  std::string out = "out/ghost_static";
  std::size_t particles = 50000;       // inner particles per geometry (Figs. 6-8)
  std::size_t cost_particles = 1000000;  // random inner particles for Table 1
  int draws = 10;                      // random draws for Table 1
  unsigned seed = 1;
  bool plots = true;
  bool relax_with_mirror = false;      // stage-2 relaxation with mirror ghosts instead of Psi
};

void write_fig5(const Options& opt);     // fig5.csv, fig5_branch.csv
void run_static(const Options& opt);     // profile_<geometry>.csv, particles_<geometry>.csv, static_summary.csv
void run_cost_table(const Options& opt); // table1.csv

}  // namespace ghost_static
