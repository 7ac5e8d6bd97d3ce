// "leapfrog-blocks" (block_leapfrog_stepper.cpp): the particles' stable steps, their levels, and
// each cycle's top step.
#include <algorithm>
#include <cmath>
#include <limits>

#include "block_leapfrog_stepper.hpp"
#include "number_text.hpp"

namespace sphark::detail {

// The stable steps of all particles after an evaluation of `particles` at t: theirs afresh, the
// others' lowered by the bounds those put on them (OdeSystem::active_stable_dt).
void BlockLeapfrogStepper::update_stable_steps(Real t, const std::vector<std::size_t>& particles) {
  bound_.assign(level_.size(), 0);
  if (system_.active_stable_dt(t, eval_.data(), dy_.data(), particles, bound_.data()) != 0)
    throw CycleFailure("particle_stable_dt failed at t=" + at_time(t) + ": " + system_.last_error());
  stable_.resize(level_.size(), std::numeric_limits<Real>::infinity());
  for (std::size_t i = 0; i < level_.size(); ++i) stable_[i] = std::min(stable_[i], bound_[i]);  // the others' bounds
  for (std::size_t i : particles) stable_[i] = bound_[i];  // the active particles' own, afresh
}

// New levels for `particles` whose steps end at `tick` (fresh: the start of a cycle, no
// hysteresis across a change of the top step); a longer step only where its grid aligns.
void BlockLeapfrogStepper::assign_levels(Real t, const std::vector<std::size_t>& particles, std::int64_t tick, bool fresh) {
  for (std::size_t i : particles) {
    const Real dt = opts_.cfl_safety * stable_[i];
    if (!(dt > 0)) throw CycleFailure("particle " + std::to_string(i) + ": stable step " + at_time(dt) + " at t=" + at_time(t));
    int l = fresh ? bins_.needed_level(dt) : bins_.next_level(level_[i], dt);
    if (bins_.level_dt(l) > dt)
      throw CycleFailure("particle " + std::to_string(i) + " needs a step below top/2^" + std::to_string(kMaxLevel) +
                         " at t=" + at_time(t));
    while (tick % length(l) != 0) ++l;  // aligned with the block grid
    level_[i] = l;
    start_[i] = tick;
  }
}

// The next cycle's top step for the `rest` of the way to t_out: top_ (the last cycle shortened to
// land); with StepperOptions::fit_block_cycles the rest in m equal cycles of at most top_, m (of
// the kCyclesTried smallest) giving the least work m (sum_i 2^l_i + kEventCost N 2^max l) at the
// particles' stable steps now — particle evaluations, and events (about 2^max l per cycle), each
// of whose O(N) work (every particle's drift, the gravity tree's build, the lists' check) is
// counted as kEventCost N evaluations (the collapse at 8,486 particles: ~7 ms per event beyond
// its evaluations, 7.7 us per particle evaluation) — the ladder top/2^l shifted to fit them (with
// m = 3 it holds top_/3, top_/6, ... between top_/2 and top_/4, ...).
constexpr double kEventCost = 0.1;

BlockLeapfrogStepper::Top BlockLeapfrogStepper::next_top(Real t_out) const {
  const Real rest = t_out - t_;
  if (!opts_.fit_block_cycles) {
    if (t_ + top_ * (1 + 1e-9) < t_out) return {top_, t_ + top_};
    return {std::abs(rest - top_) > 1e-9 * top_ ? rest : top_, t_out};  // lands (within round-off of top_: its levels)
  }
  constexpr int kCyclesTried = 16;
  const int fewest = std::max(1, static_cast<int>(std::ceil(rest / (top_ * (1 + 1e-9)))));
  int best = fewest;
  double best_cost = std::numeric_limits<double>::infinity();
  for (int m = fewest; m < fewest + kCyclesTried; ++m) {
    const Real top = rest / m;
    double evaluations = 0;
    int deepest = 0;
    for (const Real s : stable_) {
      const int l = std::min(kMaxLevel, std::max(0, std::ilogb(top / (opts_.cfl_safety * s)) + 1));
      evaluations += std::ldexp(1.0, l);
      deepest = std::max(deepest, l);
    }
    const double cost = m * (evaluations + kEventCost * static_cast<double>(stable_.size()) * std::ldexp(1.0, deepest));
    if (cost < best_cost) best_cost = cost, best = m;
  }
  return {rest / best, best == 1 ? t_out : t_ + rest / best};
}

}  // namespace sphark::detail
