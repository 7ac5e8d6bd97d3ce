#pragma once
// The three cases of the cylinder-lattice example (seed 004, §8): single run, medium resolution
// (§8.1, Fig. 9) and the low-resolution ensemble (§8.2, Fig. 10).
#include <filesystem>
#include <string>
#include <vector>

#include "sphark/cli/options.hpp"
#include "sphark/run/checkpoint.hpp"
#include "sphark/run/restart.hpp"
#include "sphark/scenes/cylinder_lattice_run.hpp"

namespace cylinder_lattice {

struct Settings {
  sphark::CoreOptions core;
  sphark::LatticeRunConfig run;     // params (map, v0, ...), particles, seed, t_end, stepper
  std::vector<std::string> maps;    // "mirror", "nonlinear"
  std::vector<sphark::Real> v0s;    // ensemble
  int seeds = 20;                   // ensemble: seeds 1..seeds
  std::string kase = "single", bc = "free-slip";
  sphark::RunControlOptions control;            // --checkpoint-every, --restart, --inject-nan-at
  std::vector<std::string> argv;                // this run's options (stored in checkpoints)
  const sphark::Checkpoint* restart = nullptr;  // --restart: continue this map's run
};

// The scene parameters of one single/medium run ("key=value" lines), stored in its checkpoint: a
// restart must give the same text.
std::string scene_text(const Settings& s, const std::string& map);

sphark::GhostMap parse_map(const std::string& name);

// Each returns the process exit status: 0 ok (t_end or an event reached), 1 error, 3 a single or
// medium run failed (last good state written), 128 + signal after SIGINT/SIGTERM.
int run_single(const Settings& s);
int run_medium(const Settings& s);
int run_ensemble_case(const Settings& s);

}  // namespace cylinder_lattice
