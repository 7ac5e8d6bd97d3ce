#include "sphark/study/study_run.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <exception>
#include <limits>

#include "sphark/integrate/stepper.hpp"
#include "sphark/run/signals.hpp"
#include "sphark/run/time_loop.hpp"  // kStepFloorFraction

namespace sphark {

std::string to_string(StudyMode mode) {
  switch (mode) {
    case StudyMode::Capped: return "capped";
    case StudyMode::Uncapped: return "uncapped";
    case StudyMode::Fixed: return "fixed";
  }
  return "?";
}

StepperOptions study_stepper_options(const StudyCase& c, const StudyProblem& problem, const StudyScene& scene,
                                     const StudyLimits& limits) {
  StepperOptions o;
  o.method = c.method;
  o.rtol = c.rtol > 0 ? c.rtol : 1e-6;
  o.atol = problem.absolute_tolerance(o.rtol);
  o.cfl_safety = limits.cap_cfl;
  o.cap_by_stability = c.mode == StudyMode::Capped;
  if (c.mode == StudyMode::Fixed) o.fixed_dt = c.cfl * scene.cfl_unit();
  o.max_steps = 200000;
  return o;
}

namespace {
bool all_finite(const std::vector<Real>& y) {
  return std::all_of(y.begin(), y.end(), [](Real v) { return std::isfinite(v); });
}
}  // namespace

StudyResult run_study_case(const StudyScene& scene, const StudyCase& c, const StudyLimits& limits) {
  StudyResult r;
  std::unique_ptr<StudyProblem> problem = scene.build();
  OdeSystem& sys = problem->system();
  std::vector<Real> y = problem->y0();
  const std::vector<Real> times = limits.times.empty() ? scene.output_times() : limits.times;
  const bool check_energy = limits.energy_tolerance > 0;
  const Real e0 = check_energy ? problem->energy(0.0, y.data()) : 0;
  double cpu = 0;
  try {
    StepperOptions so = study_stepper_options(c, *problem, scene, limits);
    so.interrupt = [] { return stop_requested() != 0; };  // SIGINT/SIGTERM: the case ends at its next RHS
    so.step_floor = kStepFloorFraction * scene.t_end();
    auto stepper = make_stepper(sys, so, 0.0, y.data());
    Real t = 0;
    for (Real t_out : times) {
      const std::clock_t start = std::clock();
      const AdvanceStatus st = stepper->advance(t_out, y.data(), t);
      cpu += static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
      r.stats = stepper->stats();
      r.t_reached = t;
      if (st == AdvanceStatus::Interrupted) {
        r.status = "stopped";
        r.failure = "stopped by signal " + std::to_string(stop_requested());
        break;
      }
      if (st == AdvanceStatus::Failed) {
        r.status = "failed";
        r.failure = stepper->failure_reason();
        break;
      }
      if (!all_finite(y)) {
        r.status = "nonfinite";
        r.failure = "non-finite state at t=" + std::to_string(t);
        break;
      }
      if (check_energy) {  // outside the CPU timing: a diagnostic, not part of the method's work
        const Real e = problem->energy(t, y.data());
        const Real change = std::abs(e - e0) / std::abs(e0);
        r.max_energy_change = std::max(r.max_energy_change, std::isfinite(change) ? change : INFINITY);
        if (!(change <= limits.energy_tolerance)) {
          r.status = "blowup";
          r.failure = "energy change " + std::to_string(change) + " at t=" + std::to_string(t);
          break;
        }
      }
      r.states.push_back(y);
      r.times.push_back(t);
      if (r.stats.rhs_evals > limits.max_rhs_evals) {
        r.status = "budget";
        r.failure = "more than " + std::to_string(limits.max_rhs_evals) + " RHS evaluations";
        break;
      }
    }
  } catch (const std::exception& e) {
    r.status = "failed";
    r.failure = e.what();
  }
  r.cpu_seconds = cpu;
  return r;
}

StudyErrors study_errors(const StudyScene& scene, const StudyResult& run, const StudyResult& reference) {
  StudyErrors e;
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  if (run.states.empty()) return {nan, nan, nan};
  // max that propagates NaN (a scene without an exact solution or without positions)
  const auto take = [](Real& m, Real v) { m = std::isnan(v) || std::isnan(m) ? std::numeric_limits<Real>::quiet_NaN() : std::max(m, v); };
  for (std::size_t k = 0; k < run.states.size(); ++k) {
    take(e.exact, scene.exact_error(run.times[k], run.states[k].data()));
    if (k < reference.states.size()) {
      take(e.time, scene.time_error(run.states[k].data(), reference.states[k].data()));
      take(e.position, scene.position_error(run.states[k].data(), reference.states[k].data()));
    }
  }
  return e;
}

}  // namespace sphark
