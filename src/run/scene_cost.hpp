#pragma once
// The cost estimate of one run of a scene (run/cost_estimate.hpp): its probe, measured before
// anything is written, and the first line of the run once it is built. Private to src/run/.
#include <string>

#include "sphark/run/cost_estimate.hpp"
#include "sphark/run/scene.hpp"

namespace sphark::detail {

struct PlannedCost {
  bool known = false;  // the scene predicts its particles and has a probe
  CostEstimate memory;
  ProbeMeasurement probe;
};

// Probes run `run`; a run that would not fit in memory is p.fail(scene.size_option(), ...), exit
// 2 (as is a value the scene's probe rejects with std::invalid_argument).
PlannedCost plan_cost(Scene& scene, const std::string& run, const CoreOptions& core, const OptionParser& p);

// The run's first line (cost_line), with its steps and time from the built run at (t0, y0);
// longest_step: the diagnostics interval (estimate_time).
std::string first_line(const std::string& program, const std::string& run, const PlannedCost& cost, SceneRun& built,
                       const StepperOptions& so, Real t0, const Real* y0, Real t_end, Real longest_step);

}  // namespace sphark::detail
