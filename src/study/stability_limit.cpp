#include "sphark/study/stability_limit.hpp"

#include <cmath>
#include <limits>

#include "sphark/run/signals.hpp"

namespace sphark {

StabilityLimit find_stability_limit(const StudyScene& scene, const std::string& method, const StabilitySettings& s) {
  StabilityLimit out;
  out.method = method;
  const Real horizon = s.horizon > 0 ? s.horizon : scene.t_end();
  StudyLimits limits;
  limits.energy_tolerance = s.energy_tolerance;
  limits.max_rhs_evals = s.max_rhs_evals;

  // Stable: the horizon is reached with finite states and the energy within tolerance.
  // (A trial stopped by the RHS budget is neither: it counts as stable, the budget only
  // bounds the cost of tiny steps.)
  const auto trial = [&](Real cfl, std::string& reason) {
    ++out.trials;
    // Check times on whole steps (n dt), so that no step is shortened to land on one: the trial
    // is a pure fixed-step run of ceil(horizon / dt) steps.
    const Real dt = cfl * scene.cfl_unit();
    const long steps = static_cast<long>(std::ceil(horizon / dt - 1e-9));
    limits.times.clear();
    for (int k = 1; k <= s.checks; ++k) {
      const long n = (steps * k + s.checks - 1) / s.checks;
      if (limits.times.empty() || n * dt > limits.times.back()) limits.times.push_back(static_cast<Real>(n) * dt);
    }
    const StudyResult r = run_study_case(scene, {method, StudyMode::Fixed, 0, cfl}, limits);
    if (r.status == "stopped") throw StopRequested{stop_requested()};  // no limit from a cut-short trial
    out.cpu_seconds += r.cpu_seconds;
    reason = r.status + (r.failure.empty() ? "" : ": " + r.failure);
    return r.ok() || r.status == "budget";
  };

  std::string reason;
  Real lo = 0, hi = std::numeric_limits<Real>::infinity();
  if (trial(s.start, reason)) {
    lo = s.start;
    for (Real c = 2 * s.start; c <= s.max_cfl; c *= 2) {
      if (trial(c, reason)) {
        lo = c;
      } else {
        hi = c;
        out.unstable_reason = reason;
        break;
      }
    }
  } else {
    hi = s.start;
    out.unstable_reason = reason;
    for (Real c = 0.5 * s.start; c >= s.min_cfl; c *= 0.5) {
      if (trial(c, reason)) {
        lo = c;
        break;
      }
      hi = c;
      out.unstable_reason = reason;
    }
  }
  if (lo > 0 && std::isfinite(hi)) {
    for (int i = 0; i < s.iterations; ++i) {
      const Real mid = std::sqrt(lo * hi);
      if (trial(mid, reason)) {
        lo = mid;
      } else {
        hi = mid;
        out.unstable_reason = reason;
      }
    }
  }
  out.cfl_stable = lo;
  out.cfl_unstable = hi;
  return out;
}

}  // namespace sphark
