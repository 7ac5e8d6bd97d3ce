#pragma once
// One water-drop run (cleaned or control): integrate, write VTK frames and diagnostics.csv,
// and summarise the accuracy against the exact ellipse.
#include <filesystem>
#include <string>

#include "sphark/cli/options.hpp"
#include "sphark/integrate/stepper_options.hpp"
#include "sphark/scenes/water_drop.hpp"

namespace sphark {

struct DropRunSettings {
  CoreOptions core;          // out is this run's directory
  WaterDropConfig scene;
  Real diagnostics_every = 1e-4;
  bool quiet = false;
};

struct DropRunSummary {
  bool ok = false;
  std::string failure;               // why the stepper gave up, if !ok
  Real t_reached = 0;
  double wall_seconds = 0;
  StepperStats stats;
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

// Runs to core.t_end. Writes <out>/diagnostics.csv, <out>/drop_*.vtp, <out>/drop.pvd.
DropRunSummary run_water_drop(const DropRunSettings& settings);

// Per-entry absolute tolerances: --atol times each field's natural scale (R, A R, rho0, and
// rho0 c_h A R for psi, which has units of pressure).
std::vector<Real> drop_absolute_tolerances(const WaterDrop& drop, Real atol);

}  // namespace sphark
