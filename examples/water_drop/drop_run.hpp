#pragma once
// One water-drop run (cleaned or control): integrate, write VTK frames and diagnostics.csv,
// and summarise the accuracy against the exact ellipse.
#include <filesystem>
#include <string>
#include <vector>

#include "sphark/cli/options.hpp"
#include "sphark/integrate/stepper_options.hpp"
#include "sphark/run/checkpoint.hpp"
#include "sphark/run/time_loop.hpp"
#include "sphark/scenes/water_drop.hpp"

namespace sphark {

struct DropRunSettings {
  CoreOptions core;          // out is this run's directory
  WaterDropConfig scene;
  Real diagnostics_every = 1e-4;
  bool quiet = false;
  std::string label = "run";        // "cleaned" / "control": stored in checkpoints
  std::vector<std::string> argv;    // options of this run, stored in checkpoints
  Real checkpoint_every = 0;        // > 0: <out>/checkpoint.bin every this much time and at the end
  const Checkpoint* restart = nullptr;  // continue from this checkpoint
  Real inject_nan_at = 0;           // > 0: testing aid, the RHS turns non-finite from this time on
};

struct DropRunSummary {
  TimeLoopResult loop;               // the run driver's outcome: status, reason, t reached, stats, ...
  std::size_t particles = 0;
  Real max_semi_axis_error = 0;      // max over samples of the relative semi-axis error
  Real time_of_max_error = 0;
  Real squeeze_error = 0;            // relative error of semi_axis_x at the first squeeze
  Real mean_abs_div_v_time_avg = 0;  // time average of the particle mean |div v|
  Real max_rel_density_error = 0;    // max over time
  Real kinetic_energy_end = 0;
  Real total_energy_drift = 0;       // (E(t_end) - E(0)) / E(0)
  long neighbour_builds = 0;
};

// Runs to core.t_end (from settings.restart if set). Writes <out>/diagnostics.csv,
// <out>/drop_*.vtp, <out>/drop.pvd (all atomically) and <out>/checkpoint.bin: every
// checkpoint_every and at the end if checkpoint_every > 0, and always when the stepper fails
// (the last good state, also written as a VTK frame) or a stop signal arrives.
DropRunSummary run_water_drop(const DropRunSettings& settings);

// The scene parameters as "key=value" lines (a restart must not change them).
std::string scene_text(const WaterDropConfig& c);

}  // namespace sphark
