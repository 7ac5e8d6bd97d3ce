#pragma once
// Largest stable fixed step of a method, as a CFL number, by bisection.
//
// A trial at CFL number C integrates the scene with dt = C * scene.cfl_unit() over a fixed
// horizon and is UNSTABLE if the stepper fails (e.g. an RHS failure it cannot recover from),
// the state turns non-finite, or the energy moves by more than energy_tolerance * |E0| at any
// of `checks` check times. The trial takes ceil(horizon / dt) whole steps and the check times
// are whole multiples of dt (no step is shortened to land on a check time). The bracket [stable, unstable] is found by doubling/halving
// from `start`, then bisected geometrically `iterations` times.
#include <string>
#include <vector>

#include "sphark/study/study_run.hpp"

namespace sphark {

struct StabilitySettings {
  Real horizon = 0;             // 0: the scene's t_end
  int checks = 20;
  Real energy_tolerance = 0.01;
  Real start = 0.5;
  int iterations = 6;
  Real min_cfl = 1.0 / 64;
  Real max_cfl = 16;
  long max_rhs_evals = 400000;
};

struct StabilityLimit {
  std::string method;
  Real cfl_stable = 0;    // largest CFL found stable (0: none down to min_cfl)
  Real cfl_unstable = 0;  // smallest CFL found unstable (inf: none up to max_cfl)
  std::string unstable_reason;  // what the smallest unstable trial hit
  int trials = 0;
  double cpu_seconds = 0;
};

// Throws StopRequested (run/signals.hpp) when a trial is stopped by SIGINT/SIGTERM.
StabilityLimit find_stability_limit(const StudyScene& scene, const std::string& method,
                                    const StabilitySettings& settings);

}  // namespace sphark
