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
#include "sphark/io/pvtp_series.hpp"
#include "sphark/run/run_outputs.hpp"
#include "sphark/run/signals.hpp"

namespace sphark {
namespace {

// t_end on the sampling grid when it is a multiple of the grid step (to 1e-9), so that a run to
// t1 and a run to t2 > t1 stop at bit-identical times on the way (restart agreement).
Real snap_to_grid(Real t_end, Real every) {
  const Real k = std::round(t_end / every);
  return k >= 1 && std::abs(t_end / every - k) < 1e-9 ? k * every : t_end;
}

// Counts of the stepper(s) before a restart, kept in the checkpoint under these names.
struct CountBase {
  Real steps = 0, attempts = 0, rhs_evals = 0, rhs_evals_implicit = 0, error_test_failures = 0,
       nonlinear_failures = 0, rhs_recoveries = 0, linear_solves = 0, particle_evals = 0;
  std::vector<std::pair<const char*, Real*>> bind() {
    return {{"steps", &steps}, {"attempts", &attempts}, {"rhs_evals", &rhs_evals},
            {"rhs_evals_implicit", &rhs_evals_implicit}, {"error_test_failures", &error_test_failures},
            {"nonlinear_failures", &nonlinear_failures}, {"rhs_recoveries", &rhs_recoveries},
            {"linear_solves", &linear_solves}, {"particle_evals", &particle_evals}};
  }
  StepperStats total(StepperStats st) const {
    st.steps += static_cast<long>(steps);
    st.attempts += static_cast<long>(attempts);
    st.rhs_evals += static_cast<long>(rhs_evals);
    st.rhs_evals_implicit += static_cast<long>(rhs_evals_implicit);
    st.error_test_failures += static_cast<long>(error_test_failures);
    st.nonlinear_failures += static_cast<long>(nonlinear_failures);
    st.rhs_recoveries += static_cast<long>(rhs_recoveries);
    st.linear_solves += static_cast<long>(linear_solves);
    st.particle_evals += static_cast<long>(particle_evals);
    return st;
  }
  void set(const StepperStats& st) {
    steps = st.steps, attempts = st.attempts, rhs_evals = st.rhs_evals, rhs_evals_implicit = st.rhs_evals_implicit;
    error_test_failures = st.error_test_failures, nonlinear_failures = st.nonlinear_failures;
    rhs_recoveries = st.rhs_recoveries, linear_solves = st.linear_solves, particle_evals = st.particle_evals;
  }
};

// Advances to t_out: in one call, or (with hooks.after_step) step by step, resizing the state and
// the stepper when the hook asks for it; `progress` is called after each step.
AdvanceStatus advance_to(Stepper& stepper, const TimeLoopHooks& hooks, Real t_out, std::vector<Real>& y, Real& t,
                         StateLayout& layout, const std::function<void()>& progress) {
  if (!hooks.after_step) return stepper.advance(t_out, y.data(), t);
  for (;;) {
    const AdvanceStatus st = stepper.step(t_out, y.data(), t);
    progress();
    if (st != AdvanceStatus::Stepped && st != AdvanceStatus::Reached) return st;
    if (std::optional<TimeLoopHooks::Resize> r = hooks.after_step(t, y.data())) {
      if (r->y.size() != r->layout.size()) throw std::logic_error("after_step: the new state does not fit its layout");
      layout = std::move(r->layout);
      y = std::move(r->y);
      stepper.resize({y.data(), r->atol.empty() ? nullptr : r->atol.data(), nullptr});
    }
    if (st == AdvanceStatus::Reached) return st;
  }
}

// The first index k of the grid k x every after t (a checkpoint time t on the grid gives the next).
Real grid_index_after(Real t, Real every) { return std::floor(t / every * (1 + 1e-12)) + 1; }

// One run of the loop: its outputs (diagnostics CSV, VTK series, checkpoints), the state, the
// stepper, the grid position and the counts before a restart.
class TimeLoop {
 public:
  TimeLoop(OdeSystem& system, const StateLayout& initial_layout, StepperOptions opts, std::vector<Real> y0,
           const TimeLoopSettings& s, const TimeLoopHooks& hooks);
  TimeLoop(const TimeLoop&) = delete;  // binds_ points into this object
  TimeLoop& operator=(const TimeLoop&) = delete;

  // Integrates to t_end, a stop, a failure or an early end; the result without its wall time.
  TimeLoopResult run();

 private:
  void bind_checkpoint_scalars();
  void restore(const Checkpoint& c);
  void bound_steps(OdeSystem& system);
  StepperStats stats() const { return base_.total(stepper_->stats()); }
  void save(Real time);
  // Distributed runs (StepperOptions::communicator with MPI): every rank writes its piece of a
  // frame (parallel VTK), rank 0 the CSV; the stop poll is collective; no checkpoints yet.
  bool distributed() const { return opts_.communicator.distributed(); }
  bool frames() const { return vtk_ || pvtk_; }
  void write_frame(Real time);
  void flush_csv() const {
    if (opts_.communicator.rank() == 0) csv_.flush();
  }
  int stop_signal() const;
  void record(Real time);
  void stop(int signal);
  void fail();
  void fail_in_hook(const std::exception& e);
  void end_at_root();
  void checkpoint_if_due();
  void finish();

  OdeSystem& system_;
  const TimeLoopSettings& s_;
  const TimeLoopHooks& hooks_;
  StepperOptions opts_;
  TimeLoopResult res_;
  const Real t_end_;
  const Real frame_every_;
  AtomicCsv csv_;
  std::optional<ResumableVtkSeries> vtk_;
  std::optional<ParallelVtkSeriesWriter> pvtk_;  // distributed runs
  Real sample_ = 0, next_frame_ = 0, next_checkpoint_;
  bool state_since_frame_ = false;  // a row was recorded after the last frame (finish() writes one)
  CountBase base_;
  std::vector<std::pair<std::string, Real*>> binds_;  // the checkpoint's scalars
  std::vector<Real> y_;
  StateLayout layout_;  // changes when after_step resizes the state
  Real t_ = 0;
  std::unique_ptr<Stepper> stepper_;
};

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
  if (s.restart) system.resume(s.restart->system_data);  // after bound_steps: its evaluation moves the starts
  stepper_ = make_stepper(system, opts_, t_, y_.data());
}

void TimeLoop::bind_checkpoint_scalars() {
  binds_ = {{"sample", &sample_}, {"next_frame", &next_frame_}, {"next_checkpoint", &next_checkpoint_}};
  for (auto& [name, ptr] : base_.bind()) binds_.emplace_back(name, ptr);
  binds_.insert(binds_.end(), hooks_.state.begin(), hooks_.state.end());
}

void TimeLoop::restore(const Checkpoint& c) {
  if (hooks_.restart_layout) layout_ = hooks_.restart_layout(c);
  if (auto why = layout_mismatch(c, layout_)) throw std::runtime_error("--restart: " + *why);
  y_ = c.y;
  t_ = c.t;
  for (auto& [name, ptr] : binds_) {
    // particle_evals (issue #17) is newer than the other counts: a checkpoint without it counts
    // from the restart on.
    const bool optional = name == "particle_evals";
    *ptr = !optional || c.has_scalar(name) ? c.scalar(name) : 0;
  }
  // Another sampling, frame or checkpoint interval than the checkpointed run's: continue on the
  // new grid from the checkpoint time on.
  if (c.scalar("sample_every") != s_.sample_every || !(sample_ * s_.sample_every > t_))  // (the latter: a corrupt index)
    sample_ = grid_index_after(t_, s_.sample_every);
  if (c.scalar("frame_every") != frame_every_) next_frame_ = grid_index_after(t_, frame_every_) * frame_every_;
  if (c.scalar("checkpoint_every") != s_.checkpoint_every && s_.checkpoint_every > 0)
    next_checkpoint_ = grid_index_after(t_, s_.checkpoint_every) * s_.checkpoint_every;
  csv_.restore(c.text("diagnostics.csv"));
  if (vtk_)  // frames_dir: absent in checkpoints of before 2026-12-02
    vtk_->restore(c.text("frames"), c.has_text("frames_dir") ? std::filesystem::path(c.text("frames_dir")) : "");
  opts_.initial_dt = c.last_dt;
  opts_.resume_data = c.stepper_data;
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

void TimeLoop::save(Real time) {
  if (distributed()) {  // checkpoints of distributed runs: not yet (the options refuse them)
    flush_csv();
    return;
  }
  ScopedPhase phase(Phase::Output);
  Checkpoint c;
  c.program = s_.program;
  c.argv = s_.argv;
  c.species = describe_layout(layout_);
  c.t = time;
  c.last_dt = stepper_->stats().last_dt > 0 ? stepper_->stats().last_dt : opts_.initial_dt;
  CountBase now;  // the counts so far: the restart's base
  now.set(stats());
  for (auto& [name, ptr] : binds_) {
    bool counted = false;
    for (auto& [cname, cptr] : now.bind())
      if (name == cname) c.set_scalar(name, *cptr), counted = true;
    if (!counted) c.set_scalar(name, *ptr);
  }
  c.set_scalar("sample_every", s_.sample_every);
  c.set_scalar("frame_every", frame_every_);
  c.set_scalar("checkpoint_every", s_.checkpoint_every);
  c.set_text("run", s_.run);
  for (const auto& [k, v] : s_.texts) c.set_text(k, v);
  c.set_text("diagnostics.csv", csv_.text());
  if (vtk_) {
    c.set_text("frames", vtk_->text());
    c.set_text("frames_dir", std::filesystem::absolute(s_.frames_dir).string());
  }
  c.y = y_;
  c.stepper_data = stepper_->resume_data();
  c.system_data = system_.resume_data();
  flush_csv();
  res_.checkpoint = s_.checkpoint;
  save_checkpoint(s_.checkpoint, c);
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

// y, t: the last good state, written as a row, a frame and a checkpoint.
void TimeLoop::fail() {
  res_.status = TimeLoopStatus::Failed;
  res_.failure = stepper_->failure_reason();
  {
    ScopedPhase phase(Phase::Output);
    csv_.row(hooks_.diagnostics(t_, y_.data(), stats()));
    if (frames()) write_frame(t_);
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

// A checkpoint at the first sample at or after every multiple of checkpoint_every.
void TimeLoop::checkpoint_if_due() {
  if (!(s_.checkpoint_every > 0 && t_ >= next_checkpoint_ - 1e-12 * t_end_)) return;
  if ((t_ - next_checkpoint_) / s_.checkpoint_every < 1e3) {
    while (next_checkpoint_ <= t_ + 1e-12 * t_end_) next_checkpoint_ += s_.checkpoint_every;
  } else {  // an interval far below the sampling: one jump, not a loop per interval passed
    next_checkpoint_ = grid_index_after(t_, s_.checkpoint_every) * s_.checkpoint_every;
  }
  save(t_);
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
      const AdvanceStatus st = advance_to(*stepper_, hooks_, t_out, y_, t_, layout_, report_progress);
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
  res_.diagnostics = csv_.text();
}

}  // namespace

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
  TimeLoop loop(system, initial_layout, std::move(opts), std::move(y0), s, hooks);
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
