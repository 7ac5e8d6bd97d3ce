// "leapfrog-blocks": kick-drift-kick with individual power-of-two block steps, Phantom style
// (Price et al. 2018, PASA 35 e031, §2.3.4; issue #17). One top step T (fixed_dt, else max_dt,
// shortened to land on t_out) is one cycle; particle i steps by T / 2^l_i, its level from its
// own stable step (OdeSystem::particle_stable_dt x cfl_safety, LevelPartition with hysteresis).
// Time inside a cycle counts in ticks of T / 2^kMaxLevel. With w every entry except positions:
//   start of i's step:  w_i += dt_i/2 ẇ_i                       (kick, with the last ẇ_i)
//   every event:        x += (t_next - t) v                     (drift of ALL particles)
//   end of i's step:    ẇ_i = f_i(t, x, w*) for the active set  (OdeSystem::rhs_subset)
//                       w_i += dt_i/2 ẇ_i                       (kick)
// Wake-up (the time-step limiter of Saitoh & Makino 2009, ApJ 697 L99, as Phantom's): at every
// event a particle whose stable step has fallen below its current step ends that step early,
// at the event: its drift and start kick are cut back to the elapsed part e of the step
// (x -= e (dt_i - e)/2 ẇ_old, w -= (dt_i - e)/2 ẇ_old), it is evaluated with the ending
// particles and kicked by e/2 ẇ_new, then binned afresh. A particle's stable step is its own at
// its last evaluation, lowered by the bounds that the particles evaluated since put on it
// (OdeSystem::active_stable_dt after every event's evaluation: a system that wants neighbours'
// steps to bound each other, as SPH does, puts those bounds there; by default every particle's
// own step at every event).
// w* predicts every particle's w to the event time from its last kick: w_j + (t - t_mid_j) ẇ_j,
// t_mid_j the middle of j's current step (for an active particle: the leapfrog's predictor
// w_half + dt/2 ẇ_n, as in "leapfrog"). An ending particle takes a new level at once if it
// needs a shorter step, a longer one only where that step's grid aligns with the current tick.
// All levels meet at the end of the cycle; there (t, y) is synchronised and returned.
// Particles removed inside the cycle (StepperOptions::remove_active: gas accreted onto a sink,
// or made into one, among the active particles; Phantom makes sinks so, ptmass.F90 "CHECK 3"):
// after an event's kicks the system may remove some of that event's active particles,
// whose every entry is then at the event's time; the others' entries and derivatives, levels,
// step starts and stable steps (taken at the evaluation, before the removal) move with them, a
// new particle (a sink) is evaluated there and takes its stable step, and the cycle goes on. No
// other evaluation is added: the next kicks use the last derivatives (Phantom does not
// re-evaluate after accretion either).
// StepperOptions::wake_next names particles to be woken at the next event (a sink candidate's
// neighbourhood, which must be all active for the sink to be made).
//
// With one level for all particles this is the global "leapfrog" KDK. Across levels, linear
// momentum is conserved only to the time-stepping error, not to round-off: a pair force is
// sampled at different times for its two particles (the usual individual-step scheme;
// Pelupessy, Jänes & Portegies Zwart 2012, New Astron. 17, 711, build momentum-conserving
// ones by splitting the pair interactions).
#include "block_leapfrog_stepper.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>

#include "sphark/core/profile.hpp"
#include "sphark/integrate/callback_errors.hpp"
#include "number_text.hpp"

namespace sphark::detail {

BlockLeapfrogStepper::BlockLeapfrogStepper(OdeSystem& system, const StepperOptions& opts, Real t0, const Real* y0)
    : system_(system), opts_(opts), top_(opts.fixed_dt > 0 ? opts.fixed_dt : opts.max_dt), n_(system.size()),
      np_(system.position_size()), xp_(system.position_offset()), vp_(system.velocity_offset()),
      owner_(system.entry_particles()), entries_(system.num_particles()), t_(t0), y_(y0, y0 + n_), dy_(n_),
      level_(system.num_particles(), 0), start_(system.num_particles(), 0),
      bins_(top_, kMaxLevel, opts.partition_hysteresis), level_stats_(kMaxLevel + 1) {
  index_entries();
  if (opts.remove_active && !opts.undo_removals) throw std::invalid_argument("leapfrog-blocks: remove_active without undo_removals");
  const std::vector<Real>& r = opts.resume_data;
  if (!r.empty()) {  // a restart: the derivative and levels of the run being continued
    if (r.size() != n_ + level_.size() + 1)
      throw std::invalid_argument("resume_data: " + std::to_string(r.size()) + " values, expected " +
                                  std::to_string(n_ + level_.size() + 1));
    std::copy(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(n_), dy_.begin());
    std::vector<int> levels(r.begin() + static_cast<std::ptrdiff_t>(n_), r.end() - 1);
    bins_.set_levels(levels);  // checks the range
    level_ = std::move(levels);
    fresh_ = r.back() != 0;
    rhs_evals_ = 0;
    return;
  }
  const int code = system_.rhs(t_, y_.data(), dy_.data());
  if (code != 0) throw std::runtime_error("leapfrog-blocks: initial rhs failed: " + system_.last_error());
}

std::vector<Real> BlockLeapfrogStepper::resume_data() const {
  if (failed_) return {};
  std::vector<Real> r = dy_;
  r.insert(r.end(), level_.begin(), level_.end());
  r.push_back(fresh_ || bins_.dt_top() != top_ ? 1 : 0);  // after a shortened step: bin afresh
  return r;
}

// Each particle's kicked entries (every entry but the positions), from entry_particles().
void BlockLeapfrogStepper::index_entries() {
  owner_ = system_.entry_particles();
  entries_.assign(system_.num_particles(), {});
  if (owner_.size() != n_) throw std::logic_error("entry_particles: not one particle per state entry");
  for (std::size_t k = 0; k < n_; ++k)
    if (k < xp_ || k >= xp_ + np_) entries_.at(owner_[k]).push_back(k);
  for (std::size_t i = 0; i < entries_.size(); ++i)  // e.g. num_particles() overridden, entry_particles() not
    if (entries_[i].empty())
      throw std::logic_error("entry_particles: particle " + std::to_string(i) + " owns no kicked state entry");
}

// The system's sizes and offsets, and its entries' particles (after its particles changed).
void BlockLeapfrogStepper::reindex() {
  n_ = system_.size(), np_ = system_.position_size(), xp_ = system_.position_offset(), vp_ = system_.velocity_offset();
  index_entries();
}

void BlockLeapfrogStepper::resize(const Resized& state) {
  if (state.y == nullptr) throw std::invalid_argument("resize: no state");
  reindex();
  y_.assign(state.y, state.y + n_);
  dy_.assign(n_, 0);
  level_.assign(entries_.size(), 0);
  start_.assign(entries_.size(), 0);
  fresh_ = true;
  if (failed_) return;
  if (state.carried) {
    std::copy(state.carried, state.carried + n_, dy_.begin());
  } else {
    ++rhs_evals_;
    if (const int code = system_.rhs(t_, y_.data(), dy_.data()); code != 0) {
      failed_ = true;
      failure_ = "leapfrog-blocks: rhs after resize returned " + std::to_string(code) + ": " + system_.last_error();
    }
  }
}

void BlockLeapfrogStepper::kick(const std::vector<std::size_t>& particles, Real factor, std::vector<Real>& w) const {
  for (std::size_t i : particles) {
    const Real h = factor * static_cast<Real>(length(level_[i])) * tick_dt_;
    for (std::size_t k : entries_[i]) w[k] += h * dy_[k];
  }
}

std::vector<std::size_t> BlockLeapfrogStepper::ending_at(std::int64_t tick) const {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < level_.size(); ++i)
    if (start_[i] + length(level_[i]) == tick) out.push_back(i);
  return out;
}

void BlockLeapfrogStepper::count(const std::vector<std::size_t>& active) {
  std::vector<char> seen(kMaxLevel + 1, 0);
  for (std::size_t i : active) {
    ++level_stats_[level_[i]].particle_evals;
    if (!seen[level_[i]]) seen[level_[i]] = 1, ++level_stats_[level_[i]].rhs_evals, ++level_stats_[level_[i]].steps;
  }
}

// Every particle's w predicted to the event (w*), into eval_: one pass over the entries (the
// positions as they are), each led from the middle of its particle's step.
void BlockLeapfrogStepper::predict(std::int64_t tick) {
  lead_.resize(level_.size());
  for (std::size_t j = 0; j < level_.size(); ++j)
    lead_[j] = (static_cast<Real>(tick - start_[j]) - 0.5 * static_cast<Real>(length(level_[j]))) * tick_dt_;
  eval_.resize(n_);
  const auto led = [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) eval_[k] = w_[k] + lead_[owner_[k]] * dy_[k];
  };
  led(0, xp_);
  std::copy(w_.begin() + static_cast<std::ptrdiff_t>(xp_), w_.begin() + static_cast<std::ptrdiff_t>(xp_ + np_),
            eval_.begin() + static_cast<std::ptrdiff_t>(xp_));
  led(xp_ + np_, n_);
}

// The particles whose step goes on past `tick` and whose stable step is below it, from the stable
// steps as of the last rebin (at the previous event, after its evaluation: one active_stable_dt
// per event, the wake-up one event later); and those StepperOptions::wake_next named at the
// previous event.
std::vector<std::size_t> BlockLeapfrogStepper::woken_at(std::int64_t tick) const {
  Real level_dt[kMaxLevel + 1];
  for (int l = 0; l <= kMaxLevel; ++l) level_dt[l] = bins_.level_dt(l);
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < level_.size(); ++i)
    if (start_[i] + length(level_[i]) > tick && (opts_.cfl_safety * stable_[i] < level_dt[level_[i]] ||
                                                 std::binary_search(wake_next_.begin(), wake_next_.end(), i)))
      out.push_back(i);
  return out;
}

// A woken particle's step is cut to its elapsed part e: the drift and the start kick it got with
// the step's full length become those of a step of length e.
void BlockLeapfrogStepper::cut_back(const std::vector<std::size_t>& woken, std::int64_t tick) {
  for (std::size_t i : woken) {
    const Real e = static_cast<Real>(tick - start_[i]) * tick_dt_, full = static_cast<Real>(length(level_[i])) * tick_dt_;
    for (std::size_t k : entries_[i]) {
      w_[k] -= 0.5 * (full - e) * dy_[k];
      if (k >= vp_ && k < vp_ + np_) w_[xp_ + (k - vp_)] -= e * 0.5 * (full - e) * dy_[k];
    }
    ++wakeups_;
  }
}

// The active particles' derivatives at (t, eval_).
void BlockLeapfrogStepper::evaluate(Real t, const std::vector<std::size_t>& active) {
  if (opts_.interrupt && opts_.interrupt()) throw CycleInterrupted{};
  count(active);
  ++rhs_evals_;
  const int code = system_.rhs_subset(t, eval_.data(), active, out_.data());
  if (code != 0)
    throw CycleFailure("rhs returned " + std::to_string(code) + " at t=" + at_time(t) + ": " + system_.last_error());
  for (std::size_t i : active)
    for (std::size_t k : entries_[i]) dy_[k] = out_[k];
}

// The end of the active particles' steps: ending ones by half their step of the new derivative,
// woken ones (cut back) by half the elapsed part e.
void BlockLeapfrogStepper::end_kicks(const std::vector<std::size_t>& ending, const std::vector<std::size_t>& woken,
                                     std::int64_t tick) {
  kick(ending, 0.5, w_);
  for (std::size_t i : woken) {
    const Real e = static_cast<Real>(tick - start_[i]) * tick_dt_;
    for (std::size_t k : entries_[i]) w_[k] += 0.5 * e * dy_[k];
  }
}

// max over the active particles' velocity entries of |v - v*| (kicked v in w_, the predicted v*
// the evaluation saw in eval_) over the rms velocity entry of every particle (w_); 0 without
// velocities.
Real BlockLeapfrogStepper::predictor_difference(const std::vector<std::size_t>& active) const {
  Real d = 0, sum = 0;
  for (std::size_t i : active)
    for (std::size_t k : entries_[i])
      if (k >= vp_ && k < vp_ + np_) d = std::max(d, std::abs(w_[k] - eval_[k]));
  for (std::size_t k = vp_; k < vp_ + np_; ++k) sum += w_[k] * w_[k];
  return sum > 0 ? d / std::sqrt(sum / static_cast<Real>(np_)) : 0;
}

// Phantom's corrector iterations for the active particles (StepperOptions::velocity_tolerance,
// as "leapfrog"; Phantom iterates its individual steps so too): while their kicked velocities
// differ from the predicted ones the evaluation saw, evaluate them again with the kicked
// entries (positions unchanged) and redo their end kicks; at most kMaxCorrectorIterations, then
// the step goes on with the last.
void BlockLeapfrogStepper::correct(Real t, const std::vector<std::size_t>& active, const std::vector<std::size_t>& ending,
                                   const std::vector<std::size_t>& woken, std::int64_t tick) {
  for (int its = 0; its < kMaxBlockCorrectorIterations; ++its) {
    if (predictor_difference(active) <= opts_.velocity_tolerance) return;
    for (std::size_t i : active)
      for (std::size_t k : entries_[i]) eval_[k] = w_[k];
    evaluate(t, active);
    ++corrector_iterations_;
    for (std::size_t i : active)
      for (std::size_t k : entries_[i]) w_[k] = pre_[k];
    end_kicks(ending, woken, tick);
  }
}

// One top step: kicks at every particle's step start and end, drifts of all at every event.
void BlockLeapfrogStepper::cycle(Real t_out) {
  w_ = y_;
  eval_ = y_;
  out_.assign(n_, 0);
  pre_.assign(n_, 0);
  std::vector<std::size_t> all(level_.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  update_stable_steps(t_, all);
  const auto [top, t_end] = next_top(t_out);
  if (top != bins_.dt_top() || opts_.fit_block_cycles)  // (fitted: afresh at every cycle, the state's alone)
    bins_ = LevelPartition(top, kMaxLevel, opts_.partition_hysteresis), fresh_ = true;
  tick_dt_ = std::ldexp(top, -kMaxLevel);
  assign_levels(t_, all, 0, fresh_);
  fresh_ = false;
  wake_next_.clear();
  kick(all, 0.5, w_);
  std::int64_t tick = 0;
  Real t = t_;
  while (tick < kTicks) {
    std::int64_t next = kTicks;
    for (std::size_t i = 0; i < level_.size(); ++i) next = std::min(next, start_[i] + length(level_[i]));
    const Real dt = static_cast<Real>(next - tick) * tick_dt_;
    for (std::size_t k = 0; k < np_; ++k) w_[xp_ + k] += dt * w_[vp_ + k];
    tick = next;
    ++events_;
    t = next == kTicks ? t_end : t_ + static_cast<Real>(tick) * tick_dt_;
    const std::vector<std::size_t> ending = ending_at(tick);
    predict(tick);
    const bool last = tick == kTicks;
    const std::vector<std::size_t> woken = last ? std::vector<std::size_t>{} : woken_at(tick);
    std::vector<std::size_t> active = ending;  // (ascending)
    if (!woken.empty()) {
      cut_back(woken, tick);
      for (std::size_t i : woken) {  // their w* from the cut-back state: as at the end of a step of length e
        const Real e = static_cast<Real>(tick - start_[i]) * tick_dt_;
        for (std::size_t k : entries_[i]) {
          eval_[k] = w_[k] + 0.5 * e * dy_[k];
          if (k >= vp_ && k < vp_ + np_) eval_[xp_ + (k - vp_)] = w_[xp_ + (k - vp_)];
        }
      }
      active.insert(active.end(), woken.begin(), woken.end());
      std::sort(active.begin(), active.end());
    }
    evaluate(t, active);
    for (std::size_t i : active)
      for (std::size_t k : entries_[i]) pre_[k] = w_[k];
    end_kicks(ending, woken, tick);
    if (opts_.velocity_tolerance > 0) correct(t, active, ending, woken, tick);
    if (last) break;
    update_stable_steps(t, active);  // at the evaluated state, before a removal changes it
    remove(t, active);
    wake_next_.clear();
    if (opts_.wake_next)
      for (std::size_t i : opts_.wake_next(t, w_.data(), active)) wake_next_.push_back(i);
    std::sort(wake_next_.begin(), wake_next_.end());
    assign_levels(t, active, tick, false);
    kick(active, 0.5, w_);  // start of their next steps
  }
  y_ = w_;
  t_ = t;
  last_dt_ = static_cast<Real>(tick) * tick_dt_;
}

AdvanceStatus BlockLeapfrogStepper::step(Real t_out, Real* y, Real& t) {
  ScopedPhase timer(Phase::Advance);
  if (t_out < t_) throw std::invalid_argument("t_out=" + at_time(t_out) + ": before the current time " + at_time(t_));
  if (!failed_ && t_out > t_) {
    const std::vector<Real> y_start = y_, dy_start = dy_;
    const std::vector<int> level_start = level_;
    const Real t_start = t_;
    // the binning and the counts of that state: an interrupted cycle is taken again from it as
    // if it had never begun (a restart from its checkpoint too)
    const LevelPartition bins_start = bins_;
    const bool fresh_start = fresh_;
    const auto counts_start = std::tuple{level_stats_, events_, rhs_evals_, wakeups_, corrector_iterations_, last_dt_};
    removed_ = false;
    AdvanceStatus status = AdvanceStatus::Stepped;
    try {
      cycle(t_out);
    } catch (const CycleInterrupted&) {
      status = AdvanceStatus::Interrupted;
    } catch (...) {
      failed_ = true;
      failure_ = current_exception_message("leapfrog-blocks");
      status = AdvanceStatus::Failed;
    }
    if (status != AdvanceStatus::Stepped) {  // back to the last synchronised state
      if (removed_) {  // the system's particles of that state
        opts_.undo_removals();
        reindex();
        start_.assign(level_start.size(), 0);
      }
      y_ = y_start, dy_ = dy_start, level_ = level_start, t_ = t_start;
      bins_ = bins_start, fresh_ = fresh_start;
      std::tie(level_stats_, events_, rhs_evals_, wakeups_, corrector_iterations_, last_dt_) = counts_start;
      std::copy(y_.begin(), y_.end(), y);
      t = t_;
      return status;
    }
  }
  std::copy(y_.begin(), y_.end(), y);
  t = t_;
  if (failed_) return AdvanceStatus::Failed;
  return t_ < t_out ? AdvanceStatus::Stepped : AdvanceStatus::Reached;
}

AdvanceStatus BlockLeapfrogStepper::advance(Real t_out, Real* y, Real& t) { return detail::advance_by_steps(*this, t_out, y, t); }

// steps: events (distinct evaluation times, each a drift of all particles); levels: one entry
// per level down to the deepest used, steps = rhs_evals = the level's own steps.
StepperStats BlockLeapfrogStepper::stats() const {
  StepperStats s;
  s.steps = s.attempts = events_;
  s.rhs_evals = rhs_evals_;
  s.corrector_iterations = corrector_iterations_;
  int deepest = 0;
  for (int l = 0; l <= kMaxLevel; ++l)
    if (level_stats_[l].rhs_evals > 0) deepest = l;
  s.levels.assign(level_stats_.begin(), level_stats_.begin() + deepest + 1);
  s.last_dt = last_dt_;
  s.current_time = t_;
  return s;
}

std::unique_ptr<Stepper> make_block_leapfrog_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                                     const Real* y0) {
  return std::make_unique<BlockLeapfrogStepper>(system, opts, t0, y0);
}

}  // namespace sphark::detail
