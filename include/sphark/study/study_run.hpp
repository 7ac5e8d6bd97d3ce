#pragma once
// One run of the stepper study: a method at a tolerance (adaptive, with or without the CFL
// cap) or at a fixed CFL number, integrated through the scene's output times; process CPU
// time, stepper statistics and the state at every output time (for the errors).
#include <string>
#include <vector>

#include "sphark/integrate/stepper_options.hpp"
#include "sphark/study/study_scene.hpp"

namespace sphark {

enum class StudyMode { Capped, Uncapped, Fixed };
std::string to_string(StudyMode mode);

struct StudyCase {
  std::string method;  // ERK table, "ark-imex" or "leapfrog"
  StudyMode mode = StudyMode::Capped;
  Real rtol = 0;       // adaptive modes
  Real cfl = 0;        // Fixed: dt = cfl * scene.cfl_unit()
};

struct StudyLimits {
  Real cap_cfl = 0.25;         // adaptive Capped runs: dt <= cap_cfl * max_stable_dt
  long max_rhs_evals = 200000; // a run stops ("budget") once it has used more
  Real energy_tolerance = 0;   // > 0: stop ("blowup") when |E - E0| > energy_tolerance |E0|
  std::vector<Real> times;     // check/output times; empty = scene.output_times()
};

struct StudyResult {
  std::string status = "ok";  // ok | failed | blowup | budget | nonfinite | stopped (SIGINT/SIGTERM: not a result)
  std::string failure;        // stepper failure reason or criterion that stopped the run
  double cpu_seconds = 0;     // process CPU time (std::clock) of the integration
  StepperStats stats;
  Real t_reached = 0;
  Real max_energy_change = 0;            // max |E - E0| / |E0| over the check times (if checked)
  std::vector<std::vector<Real>> states; // state at each reached output time
  std::vector<Real> times;               // those times
  bool ok() const { return status == "ok"; }
};

StepperOptions study_stepper_options(const StudyCase& c, const StudyProblem& problem, const StudyScene& scene,
                                     const StudyLimits& limits);
StudyResult run_study_case(const StudyScene& scene, const StudyCase& c, const StudyLimits& limits);

// Errors of a finished run: max over the common output times.
struct StudyErrors {
  Real exact = 0;     // vs the scene's exact solution (total error)
  Real time = 0;      // vs the reference run (time-integration error)
  Real position = 0;  // RMS position difference vs the reference run
};
StudyErrors study_errors(const StudyScene& scene, const StudyResult& run, const StudyResult& reference);

}  // namespace sphark
