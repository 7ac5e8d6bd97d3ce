// The time loop (see sphark/run/time_loop.hpp): its run, records and ends; the checkpoint half
// is time_loop_checkpoint.cpp.
#include "sphark/run/time_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>

#include "sphark/core/profile.hpp"
#include "sphark/integrate/stepper.hpp"
#include "sphark/io/progress.hpp"
#include "sphark/run/signals.hpp"
#include "time_loop_impl.hpp"

namespace sphark {
namespace detail {
namespace {

// t_end on the sampling grid when it is a multiple of the grid step (to 1e-9), so that a run to
// t1 and a run to t2 > t1 stop at bit-identical times on the way (restart agreement).
Real snap_to_grid(Real t_end, Real every) {
  const Real k = std::round(t_end / every);
  return k >= 1 && std::abs(t_end / every - k) < 1e-9 ? k * every : t_end;
}

// The stepper continues from the state after_step returned: its carried data moved along (given,
// or following entry_source when every new entry has a source), else evaluated afresh. Present
// but empty (a rank left with no particles) still counts as given: every rank of a distributed
// run must take the same branch.
void resize_stepper(Stepper& stepper, TimeLoopHooks::Resize& r, StateLayout& layout, std::vector<Real>& y) {
  if (r.y.size() != r.layout.size()) throw std::logic_error("after_step: the new state does not fit its layout");
  const std::size_t old_size = layout.size();
  layout = std::move(r.layout);
  y = std::move(r.y);
  std::optional<std::vector<Real>> carried = std::move(r.carried);
  if (carried && carried->size() != y.size()) throw std::logic_error("after_step: carried data that does not fit the new state");
  if (!r.entry_source.empty()) {
    if (r.entry_source.size() != y.size()) throw std::logic_error("after_step: entry sources that do not fit the new state");
    const std::vector<Real> old = stepper.carried_data();
    const bool all_sourced = std::all_of(r.entry_source.begin(), r.entry_source.end(),
                                         [&](std::size_t e) { return e != kNoEntrySource; });
    for (std::size_t e : r.entry_source)
      if (e != kNoEntrySource && e >= old_size) throw std::logic_error("after_step: an entry source out of range");
    if (old.size() == old_size && all_sourced) {
      carried.emplace(y.size());
      for (std::size_t k = 0; k < y.size(); ++k) (*carried)[k] = old[r.entry_source[k]];
    }
  }
  static Real none = 0;  // the address of an empty but present carried array
  const Real* carried_data = carried ? (carried->empty() ? &none : carried->data()) : nullptr;
  stepper.resize({y.data(), r.atol.empty() ? nullptr : r.atol.data(), carried_data});
}

// Advances to t_out: in one call, or (with hooks.after_step) step by step, resizing the state and
// the stepper when the hook asks for it; `progress` is called after each step.
// `removed`: the layout after particles were removed inside the step (remove_active), whose
// state, no longer than the old one, the step wrote into y.
AdvanceStatus advance_to(Stepper& stepper, const TimeLoopHooks& hooks, Real t_out, std::vector<Real>& y, Real& t,
                         StateLayout& layout, std::optional<StateLayout>& removed,
                         const std::function<void()>& progress) {
  if (!hooks.after_step) return stepper.advance(t_out, y.data(), t);
  const TimeLoopHooks::CarriedData carried_now = [&stepper] { return stepper.carried_data(); };
  for (;;) {
    const AdvanceStatus st = stepper.step(t_out, y.data(), t);
    if (removed) {
      layout = std::move(*removed);
      removed.reset();
      y.resize(layout.size());
    }
    progress();
    if (st != AdvanceStatus::Stepped && st != AdvanceStatus::Reached) return st;
    if (std::optional<TimeLoopHooks::Resize> r = hooks.after_step(t, y.data(), carried_now))
      resize_stepper(stepper, *r, layout, y);
    if (st == AdvanceStatus::Reached) return st;
  }
}

}  // namespace

TimeLoop::TimeLoop(OdeSystem& system, const StateLayout& initial_layout, StepperOptions opts, std::vector<Real> y0,
                   const TimeLoopSettings& s, const TimeLoopHooks& hooks)
    : system_(system), s_(s), hooks_(hooks), opts_(std::move(opts)), t_end_(snap_to_grid(s.t_end, s.sample_every)),
      frame_every_(s.frame_every > 0 ? s.frame_every : t_end_), csv_(s.diagnostics_csv, s.columns),
      next_checkpoint_(s.checkpoint_every), y_(std::move(y0)), layout_(initial_layout) {
  res_.program = s.program;
  res_.run = s.run;
  if (!s.frames_dir.empty() && distributed()) pvtk_.emplace(opts_.communicator, s.frames_dir, s.frames_basename);
  if (!s.frames_dir.empty() && !distributed()) vtk_.emplace(s.frames_dir, s.frames_basename);
  bind_checkpoint_scalars();
  if (y_.size() != layout_.size()) throw std::invalid_argument("run_time_loop: initial state does not fit the layout");
  if (s.restart) restore(*s.restart);
  bound_steps(system);
  // after bound_steps: its evaluation moves the starts (distributed: this rank's share, restore_share)
  if (s.restart) system.resume(distributed() ? system_resume_ : s.restart->system_data);
  stepper_ = make_stepper(system, opts_, t_, y_.data());
}

// The stepper's limits (unless set by the caller) and the interrupt that polls for a stop signal.
void TimeLoop::bound_steps(OdeSystem& system) {
  // A blow-up ends the run instead of shrinking steps forever.
  if (opts_.min_dt <= 0) {
    const Real stable = system.max_stable_dt(t_, y_.data(), nullptr);
    const Real scale = std::isfinite(stable) && stable > 0 ? std::min(stable, s_.sample_every) : s_.sample_every;
    opts_.min_dt = s_.min_dt_fraction * scale;
  }
  if (opts_.step_floor <= 0) opts_.step_floor = s_.step_floor_fraction * t_end_;
  if (!opts_.interrupt) opts_.interrupt = [this] { return stop_signal() != 0; };
  if (!opts_.wake_next && hooks_.wake_next) opts_.wake_next = hooks_.wake_next;
  if (!opts_.remove_active && hooks_.remove_active && hooks_.restore_particles) {
    opts_.remove_active = [this](Real t, const Real* y, const std::vector<std::size_t>& active) {
      std::optional<TimeLoopHooks::Resize> r = hooks_.remove_active(t, y, active);
      if (!r) return std::optional<StepperOptions::Removal>{};
      if (r->y.size() != r->layout.size() || r->y.size() > y_.size())
        throw std::logic_error("remove_active: a state that does not fit its layout, or grew");
      removed_layout_ = std::move(r->layout);
      return std::optional<StepperOptions::Removal>{{std::move(r->y), std::move(r->entry_source)}};
    };
    opts_.undo_removals = [this] {
      hooks_.restore_particles(layout_);
      removed_layout_.reset();
    };
  }
  if (s_.inject_nan_at > 0) opts_.inject_nan_from = s_.inject_nan_at;
}

void TimeLoop::write_frame(Real time) {
  const ParticleFrame f = hooks_.frame(time, y_.data());
  res_.last_frame = pvtk_ ? pvtk_->write(f, time) : vtk_->write(f, time);
  state_since_frame_ = false;
}

// The signal a stop was requested by (0: none); distributed: of any rank, on every rank.
int TimeLoop::stop_signal() const {
  const int mine = stop_requested();
  return distributed() ? static_cast<int>(opts_.communicator.allreduce(std::int64_t(mine), ReduceOp::Max)) : mine;
}

// The diagnostics row at a grid time, and the frame when one is due.
void TimeLoop::record(Real time) {
  ScopedPhase phase(Phase::Output);
  csv_.row(hooks_.diagnostics(time, y_.data(), stats()));
  if (frames() && time >= next_frame_ - 1e-12 * t_end_) {
    write_frame(time);
    flush_csv();
    next_frame_ += frame_every_;
  } else {
    state_since_frame_ = true;
  }
  sample_ += 1;
}

void TimeLoop::stop(int signal) {
  res_.status = TimeLoopStatus::Stopped;
  res_.signal = signal;
  save(t_);
}

// y, t: the last good state, written as a row, a frame and a checkpoint. The stepper's reason
// is the failure's; if the row or the frame of that state cannot be made (a system whose own
// state was left by the failed attempt, e.g. a density solve started from its iterates), that is
// added to it, and the checkpoint is written all the same.
void TimeLoop::fail() {
  res_.status = TimeLoopStatus::Failed;
  res_.failure = stepper_->failure_reason();
  try {
    ScopedPhase phase(Phase::Output);
    csv_.row(hooks_.diagnostics(t_, y_.data(), stats()));
    if (frames()) write_frame(t_);
  } catch (const std::exception& e) {
    if (distributed()) throw;  // (run_scene ends every rank)
    res_.failure += std::string("; the last good state's row or frame: ") + e.what();
  }
  save(t_);
}

// An exception from a hook (diagnostics, frame, after_step) or the stepper's set-up, in a serial
// run: the run fails like a stepper failure, keeping what it has — the CSV rows so far and a
// checkpoint of the state reached (t_, y_: the last state the stepper accepted; the hook may be
// what failed on it, so no frame is attempted).
void TimeLoop::fail_in_hook(const std::exception& e) {
  res_.status = TimeLoopStatus::Failed;
  res_.failure = e.what();
  try {
    if (y_.size() != layout_.size()) throw std::runtime_error("the state does not fit its layout");  // mid-resize
    save(t_);
  } catch (const std::exception& again) {  // the checkpoint needs the system too: keep the rows at least
    res_.failure += std::string("; no checkpoint: ") + again.what();
    flush_csv();
  }
}

void TimeLoop::end_at_root() {
  const std::filesystem::path before = res_.last_frame;
  record(t_);  // the event ends the run at its root time, with a frame of that state
  if (frames() && res_.last_frame == before) {
    ScopedPhase phase(Phase::Output);
    write_frame(t_);
    flush_csv();
  }
  res_.status = TimeLoopStatus::EndedEarly;
}

TimeLoopResult TimeLoop::run() {
  if (hooks_.started) hooks_.started();
  ProgressReporter progress(t_, t_end_, s_.progress_interval);
  progress.set_label(s_.progress_label);
  const auto report_progress = [&] {
    if (!s_.quiet) progress.update(t_, stats().steps, stepper_->stats().last_dt);
  };
  try {
    if (!s_.restart) record(0.0);
    if (hooks_.finished && hooks_.finished(t_)) res_.status = TimeLoopStatus::EndedEarly;
    while (res_.status == TimeLoopStatus::Reached && t_ < t_end_ * (1 - 1e-12)) {
      if (const int sig = stop_signal()) {  // SIGINT/SIGTERM: checkpoint the last recorded state
        stop(sig);
        break;
      }
      const Real t_out = std::min(t_end_, sample_ * s_.sample_every);
      const AdvanceStatus st = advance_to(*stepper_, hooks_, t_out, y_, t_, layout_, removed_layout_, report_progress);
      if (st == AdvanceStatus::Interrupted) {  // mid-interval: checkpoint the last accepted step
        stop(stop_signal());
        break;
      }
      if (st == AdvanceStatus::Failed) {
        fail();
        break;
      }
      if (st == AdvanceStatus::RootFound) {
        if (!hooks_.root || !hooks_.root(t_, stepper_->roots_found())) continue;
        end_at_root();
        break;
      }
      record(t_);
      if (hooks_.finished && hooks_.finished(t_)) res_.status = TimeLoopStatus::EndedEarly;
      checkpoint_if_due();
      report_progress();
    }
  } catch (const std::exception& e) {
    // Distributed: one rank's exception cannot be answered here (the others may wait in a
    // collective); run_scene aborts every rank.
    if (distributed()) throw;
    fail_in_hook(e);
  }
  if (!s_.quiet) progress.finish();
  finish();
  return std::move(res_);
}

// After the loop: the CSV, a frame of the final state when the frame grid did not end on it
// (t_end not a multiple of the frame interval, or a run that ended early), and with checkpoints
// one at the end, of a run that ended well; and the result's totals.
void TimeLoop::finish() {
  if (res_.ok()) {
    {
      ScopedPhase phase(Phase::Output);
      if (frames() && state_since_frame_) write_frame(t_);
      flush_csv();
    }
    if (s_.checkpoint_every > 0) save(t_);
  }
  res_.t_reached = t_;
  res_.stats = stats();
  if (distributed())  // every rank's particles: the work of the whole run (the other counts are the same on every rank)
    res_.stats.particle_evals = opts_.communicator.allreduce(std::int64_t(res_.stats.particle_evals), ReduceOp::Sum);
  res_.diagnostics = csv_.text();
}

}  // namespace detail

TimeLoopResult run_time_loop(OdeSystem& system, const StateLayout& initial_layout, StepperOptions opts, std::vector<Real> y0,
                             const TimeLoopSettings& s, const TimeLoopHooks& hooks) {
  if (!(s.sample_every > 0)) throw std::invalid_argument("run_time_loop: sample_every must be positive");
  if (!hooks.diagnostics) throw std::invalid_argument("run_time_loop: no diagnostics hook");
  if (!s.frames_dir.empty() && !hooks.frame) throw std::invalid_argument("run_time_loop: frames without a frame hook");
  RunProfile& profile = run_profile();
  if (profile.enabled()) profile.reset();
  const auto start = std::chrono::steady_clock::now();
  install_stop_handlers();

  const int rank = opts.communicator.rank();
  detail::TimeLoop loop(system, initial_layout, std::move(opts), std::move(y0), s, hooks);
  TimeLoopResult res = loop.run();
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (profile.enabled() && rank == 0) {  // distributed: rank 0's profile
    std::cout << s.program << " " << s.run << ": ";
    profile.print(std::cout, res.wall_seconds);
    std::cout.flush();
  }
  return res;
}

}  // namespace sphark
