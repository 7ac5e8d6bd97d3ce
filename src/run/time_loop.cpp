#include "sphark/run/time_loop.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "sphark/core/profile.hpp"
#include "sphark/integrate/stepper.hpp"
#include "sphark/io/progress.hpp"
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
       nonlinear_failures = 0, rhs_recoveries = 0, linear_solves = 0;
  std::vector<std::pair<const char*, Real*>> bind() {
    return {{"steps", &steps}, {"attempts", &attempts}, {"rhs_evals", &rhs_evals},
            {"rhs_evals_implicit", &rhs_evals_implicit}, {"error_test_failures", &error_test_failures},
            {"nonlinear_failures", &nonlinear_failures}, {"rhs_recoveries", &rhs_recoveries},
            {"linear_solves", &linear_solves}};
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
    return st;
  }
  void set(const StepperStats& st) {
    steps = st.steps, attempts = st.attempts, rhs_evals = st.rhs_evals, rhs_evals_implicit = st.rhs_evals_implicit;
    error_test_failures = st.error_test_failures, nonlinear_failures = st.nonlinear_failures;
    rhs_recoveries = st.rhs_recoveries, linear_solves = st.linear_solves;
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

}  // namespace

TimeLoopResult run_time_loop(OdeSystem& system, const StateLayout& initial_layout, StepperOptions opts, std::vector<Real> y0,
                             const TimeLoopSettings& s, const TimeLoopHooks& hooks) {
  if (!(s.sample_every > 0)) throw std::invalid_argument("run_time_loop: sample_every must be positive");
  if (!hooks.diagnostics) throw std::invalid_argument("run_time_loop: no diagnostics hook");
  const bool frames = !s.frames_dir.empty();
  if (frames && !hooks.frame) throw std::invalid_argument("run_time_loop: frames without a frame hook");
  RunProfile& profile = run_profile();
  if (profile.enabled()) profile.reset();
  const auto start = std::chrono::steady_clock::now();
  install_stop_handlers();

  TimeLoopResult res;
  res.program = s.program;
  res.run = s.run;
  const Real t_end = snap_to_grid(s.t_end, s.sample_every);
  const Real frame_every = s.frame_every > 0 ? s.frame_every : t_end;

  AtomicCsv csv(s.diagnostics_csv, s.columns);
  std::optional<ResumableVtkSeries> vtk;
  if (frames) vtk.emplace(s.frames_dir, s.frames_basename);
  Real sample = 0, next_frame = 0, next_checkpoint = s.checkpoint_every;
  CountBase base;
  std::vector<std::pair<std::string, Real*>> binds = {
      {"sample", &sample}, {"next_frame", &next_frame}, {"next_checkpoint", &next_checkpoint}};
  for (auto& [name, ptr] : base.bind()) binds.emplace_back(name, ptr);
  binds.insert(binds.end(), hooks.state.begin(), hooks.state.end());

  std::vector<Real> y = std::move(y0);
  StateLayout layout = initial_layout;  // changes when after_step resizes the state
  if (y.size() != layout.size()) throw std::invalid_argument("run_time_loop: initial state does not fit the layout");
  Real t = 0;
  if (s.restart) {
    const Checkpoint& c = *s.restart;
    if (hooks.restart_layout) layout = hooks.restart_layout(c);
    if (auto why = layout_mismatch(c, layout)) throw std::runtime_error("--restart: " + *why);
    y = c.y;
    t = c.t;
    for (auto& [name, ptr] : binds) *ptr = c.scalar(name);
    // Another sampling, frame or checkpoint interval than the checkpointed run's: continue on the
    // new grid from the checkpoint time on.
    if (c.scalar("sample_every") != s.sample_every || !(sample * s.sample_every > t))  // (the latter: a corrupt index)
      sample = std::floor(t / s.sample_every * (1 + 1e-12)) + 1;
    if (c.scalar("frame_every") != frame_every) next_frame = (std::floor(t / frame_every * (1 + 1e-12)) + 1) * frame_every;
    if (c.scalar("checkpoint_every") != s.checkpoint_every && s.checkpoint_every > 0)
      next_checkpoint = (std::floor(t / s.checkpoint_every * (1 + 1e-12)) + 1) * s.checkpoint_every;
    csv.restore(c.text("diagnostics.csv"));
    if (vtk) vtk->restore(c.text("frames"));
    opts.initial_dt = c.last_dt;
    opts.resume_data = c.stepper_data;
  }
  // A blow-up ends the run instead of shrinking steps forever.
  if (opts.min_dt <= 0) {
    const Real stable = system.max_stable_dt(t, y.data(), nullptr);
    const Real scale = std::isfinite(stable) && stable > 0 ? std::min(stable, s.sample_every) : s.sample_every;
    opts.min_dt = s.min_dt_fraction * scale;
  }
  if (opts.step_floor <= 0) opts.step_floor = s.step_floor_fraction * t_end;
  if (!opts.interrupt) opts.interrupt = [] { return stop_requested() != 0; };
  if (s.inject_nan_at > 0) opts.inject_nan_from = s.inject_nan_at;
  auto stepper = make_stepper(system, opts, t, y.data());
  if (hooks.started) hooks.started();
  const auto stats = [&] { return base.total(stepper->stats()); };

  const auto save = [&](Real time) {
    ScopedPhase phase(Phase::Output);
    Checkpoint c;
    c.program = s.program;
    c.argv = s.argv;
    c.species = describe_layout(layout);
    c.t = time;
    c.last_dt = stepper->stats().last_dt > 0 ? stepper->stats().last_dt : opts.initial_dt;
    CountBase now;  // the counts so far: the restart's base
    now.set(stats());
    for (auto& [name, ptr] : binds) {
      bool counted = false;
      for (auto& [cname, cptr] : now.bind())
        if (name == cname) c.set_scalar(name, *cptr), counted = true;
      if (!counted) c.set_scalar(name, *ptr);
    }
    c.set_scalar("sample_every", s.sample_every);
    c.set_scalar("frame_every", frame_every);
    c.set_scalar("checkpoint_every", s.checkpoint_every);
    c.set_text("run", s.run);
    for (const auto& [k, v] : s.texts) c.set_text(k, v);
    c.set_text("diagnostics.csv", csv.text());
    if (vtk) c.set_text("frames", vtk->text());
    c.y = y;
    c.stepper_data = stepper->resume_data();
    csv.flush();
    res.checkpoint = s.checkpoint;
    save_checkpoint(s.checkpoint, c);
  };
  const auto write_frame = [&](Real time) { res.last_frame = vtk->write(hooks.frame(time, y.data()), time); };
  const auto record = [&](Real time) {
    ScopedPhase phase(Phase::Output);
    csv.row(hooks.diagnostics(time, y.data(), stats()));
    if (vtk && time >= next_frame - 1e-12 * t_end) {
      write_frame(time);
      csv.flush();
      next_frame += frame_every;
    }
    sample += 1;
  };

  ProgressReporter progress(t, t_end, s.progress_interval);
  if (!s.restart) record(0.0);
  if (hooks.finished && hooks.finished(t)) res.status = TimeLoopStatus::EndedEarly;
  while (res.status == TimeLoopStatus::Reached && t < t_end * (1 - 1e-12)) {
    if (const int sig = stop_requested()) {  // SIGINT/SIGTERM: checkpoint the last recorded state
      res.status = TimeLoopStatus::Stopped;
      res.signal = sig;
      save(t);
      break;
    }
    const Real t_out = std::min(t_end, sample * s.sample_every);
    const AdvanceStatus st = advance_to(*stepper, hooks, t_out, y, t, layout, [&] {
      if (!s.quiet) progress.update(t, stats().steps, stepper->stats().last_dt);
    });
    if (st == AdvanceStatus::Interrupted) {  // mid-interval: checkpoint the last accepted step
      res.status = TimeLoopStatus::Stopped;
      res.signal = stop_requested();
      save(t);
      break;
    }
    if (st == AdvanceStatus::Failed) {  // y, t: the last good state
      res.status = TimeLoopStatus::Failed;
      res.failure = stepper->failure_reason();
      {
        ScopedPhase phase(Phase::Output);
        csv.row(hooks.diagnostics(t, y.data(), stats()));
        if (vtk) write_frame(t);
      }
      save(t);
      break;
    }
    if (st == AdvanceStatus::RootFound) {
      if (!hooks.root || !hooks.root(t, stepper->roots_found())) continue;
      const std::filesystem::path before = res.last_frame;
      record(t);  // the event ends the run at its root time, with a frame of that state
      if (vtk && res.last_frame == before) {
        ScopedPhase phase(Phase::Output);
        write_frame(t);
        csv.flush();
      }
      res.status = TimeLoopStatus::EndedEarly;
      break;
    }
    record(t);
    if (hooks.finished && hooks.finished(t)) res.status = TimeLoopStatus::EndedEarly;
    if (s.checkpoint_every > 0 && t >= next_checkpoint - 1e-12 * t_end) {
      if ((t - next_checkpoint) / s.checkpoint_every < 1e3) {
        while (next_checkpoint <= t + 1e-12 * t_end) next_checkpoint += s.checkpoint_every;
      } else {  // an interval far below the sampling: one jump, not a loop per interval passed
        next_checkpoint = (std::floor(t / s.checkpoint_every * (1 + 1e-12)) + 1) * s.checkpoint_every;
      }
      save(t);
    }
    if (!s.quiet) progress.update(t, stats().steps, stepper->stats().last_dt);
  }
  if (!s.quiet) progress.finish();
  if (res.ok()) {
    {
      ScopedPhase phase(Phase::Output);
      csv.flush();
    }
    if (s.checkpoint_every > 0) save(t);
  }
  res.t_reached = t;
  res.stats = stats();
  res.diagnostics = csv.text();
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (profile.enabled()) {
    std::cout << s.program << " " << s.run << ": ";
    profile.print(std::cout, res.wall_seconds);
    std::cout.flush();
  }
  return res;
}

int report_time_loop_end(const TimeLoopResult& r) {
  const char* p = r.program.c_str();
  switch (r.status) {
    case TimeLoopStatus::Reached:
    case TimeLoopStatus::EndedEarly: return 0;
    case TimeLoopStatus::Stopped:
      std::fprintf(stderr, "%s: %s run stopped by signal %d at t=%.9g; checkpoint %s (continue with --restart %s)\n", p,
                   r.run.c_str(), r.signal, r.t_reached, r.checkpoint.c_str(), r.checkpoint.c_str());
      return 128 + r.signal;
    case TimeLoopStatus::Failed:
      std::fprintf(stderr, "%s: %s run FAILED at t=%.9g: %s\n%s: last good state: %s%s%s\n", p, r.run.c_str(),
                   r.t_reached, r.failure.c_str(), p, r.last_frame.empty() ? "" : r.last_frame.c_str(),
                   r.last_frame.empty() ? "" : " and ", r.checkpoint.c_str());
      return 3;
  }
  return 1;
}

std::vector<Real> csv_column(const std::string& text, const std::string& column) {
  std::istringstream in(text);
  std::string line, cell;
  std::getline(in, line);
  std::istringstream head(line);
  int index = -1;
  for (int i = 0; std::getline(head, cell, ','); ++i)
    if (cell == column) index = i;
  if (index < 0) throw std::runtime_error("no column '" + column + "' in the diagnostics");
  std::vector<Real> out;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    for (int i = 0; std::getline(row, cell, ','); ++i)
      if (i == index) out.push_back(std::stod(cell));
  }
  return out;
}

}  // namespace sphark
