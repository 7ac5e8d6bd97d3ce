#pragma once
// The low-resolution ensemble of the cylinder lattice (seed 004, §8.2, Fig. 10): every map x v0
// x seed 1..seeds, t_max of each in ensemble.csv (and steps, RHS, CPU in ensemble_runs.csv), a
// table per map and v0, and Fig. 10. Returns the exit code (128 + signal after SIGINT/SIGTERM:
// the runs done are kept).
#include <string>
#include <vector>

#include "sphark/cli/options.hpp"
#include "sphark/scenes/cylinder_lattice/lattice_run.hpp"

namespace sphark {

int run_lattice_ensemble(const LatticeRunConfig& run, const std::vector<std::string>& maps, const std::vector<Real>& v0s,
                         int seeds, const CoreOptions& core);

}  // namespace sphark
