#include "drop_run.hpp"

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "sphark/integrate/stepper.hpp"
#include "sphark/io/csv_writer.hpp"
#include "sphark/io/progress.hpp"
#include "sphark/run/guarded_system.hpp"
#include "sphark/run/run_outputs.hpp"
#include "sphark/run/signals.hpp"

namespace sphark {

namespace {
// Point arrays of one frame; the vectors must outlive the write() call.
struct FrameBuffers {
  std::vector<Real> velocity, density, pressure, div_v, psi;
};

ParticleFrame make_frame(const WaterDrop& drop, const Real* y, FrameBuffers& buf) {
  const StateLayout& L = drop.model->layout();
  const std::size_t n = L.particles();
  const Real* v = y + L.offset(Field::Velocity);
  buf.velocity.assign(v, v + 2 * n);
  const Real* rho = y + L.offset(Field::Density);
  buf.density.assign(rho, rho + n);
  buf.pressure = drop.model->pressure();
  buf.div_v = drop.model->div_v();
  ParticleFrame f;
  f.dim = 2;
  f.count = n;
  f.positions = y + L.offset(Field::Position);
  f.arrays = {{"velocity", buf.velocity.data(), 2},
              {"density", buf.density.data(), 1},
              {"pressure", buf.pressure.data(), 1},
              {"div_v", buf.div_v.data(), 1}};
  if (L.has(Field::Psi)) {
    const Real* psi = y + L.offset(Field::Psi);
    buf.psi.assign(psi, psi + n);
    f.arrays.push_back({"psi", buf.psi.data(), 1});
  }
  return f;
}

StepperOptions stepper_options(const DropRunSettings& s, const WaterDrop& drop) {
  StepperOptions o;
  o.method = s.core.stepper;
  o.rtol = s.core.rtol;
  o.atol = water_drop_absolute_tolerances(drop, s.core.atol);
  o.fixed_dt = s.core.dt;
  return o;
}

// t_end on the diagnostics grid when it is a multiple of the grid step (to 1e-9), so that a run
// to t1 and a run to t2 > t1 stop at bit-identical times on the way (restart agreement).
Real snap_to_grid(Real t_end, Real every) {
  const Real k = std::round(t_end / every);
  return k >= 1 && std::abs(t_end / every - k) < 1e-9 ? k * every : t_end;
}

// Every number of the run loop that a restart needs, bound by name (for the checkpoint).
struct LoopState {
  Real e0 = 0, div_integral = 0, t_prev = 0, div_prev = 0, prev_exact_a = 0, prev_err_x = 0;
  Real next_frame = 0, next_checkpoint = 0, sample = 0, squeeze_seen = 0;
  Real steps = 0, attempts = 0, rhs_evals = 0, error_test_failures = 0, rhs_recoveries = 0;  // before restart
  std::vector<std::pair<const char*, Real*>> bind(DropRunSummary& sum) {
    return {{"e0", &e0}, {"div_integral", &div_integral}, {"t_prev", &t_prev}, {"div_prev", &div_prev},
            {"prev_exact_a", &prev_exact_a}, {"prev_err_x", &prev_err_x}, {"next_frame", &next_frame},
            {"next_checkpoint", &next_checkpoint}, {"sample", &sample}, {"squeeze_seen", &squeeze_seen},
            {"steps", &steps}, {"attempts", &attempts}, {"rhs_evals", &rhs_evals},
            {"error_test_failures", &error_test_failures}, {"rhs_recoveries", &rhs_recoveries},
            {"max_semi_axis_error", &sum.max_semi_axis_error}, {"time_of_max_error", &sum.time_of_max_error},
            {"squeeze_error", &sum.squeeze_error}, {"max_rel_density_error", &sum.max_rel_density_error},
            {"kinetic_energy_end", &sum.kinetic_energy_end}, {"total_energy_drift", &sum.total_energy_drift}};
  }
  StepperStats total(StepperStats st) const {  // this stepper's counts plus those before the restart
    st.steps += static_cast<long>(steps);
    st.attempts += static_cast<long>(attempts);
    st.rhs_evals += static_cast<long>(rhs_evals);
    st.error_test_failures += static_cast<long>(error_test_failures);
    st.rhs_recoveries += static_cast<long>(rhs_recoveries);
    return st;
  }
};
}  // namespace

std::string scene_text(const WaterDropConfig& c) {
  std::string s;
  const auto put = [&s](const char* key, Real v) {  // shortest text that reads back exactly
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    ((s += key) += '=').append(buf, r.ptr) += '\n';
  };
  put("radius", c.radius);
  put("spacing", c.spacing);
  put("amplitude", c.amplitude);
  put("omega", c.omega);
  put("rho0", c.rho0);
  put("sound_speed", c.sound_speed);
  put("h_factor", c.h_factor);
  ((s += "kernel=") += c.kernel) += '\n';
  put("alpha", c.alpha);
  put("diffusion_correction", c.diffusion_correction);
  put("delta", c.delta);
  put("cleaning", c.cleaning);
  put("clean_sigma", c.clean_sigma);
  put("cfl", c.cfl);
  put("exact_initial_pressure", c.exact_initial_pressure);
  return s;
}

DropRunSummary run_water_drop(const DropRunSettings& s) {
  DropRunSummary sum;
  WaterDrop drop = make_water_drop(s.scene);
  const StateLayout& layout = drop.model->layout();
  GuardedSystem sys(drop.model->system(), layout);
  if (s.inject_nan_at > 0) sys.inject_nan_from(s.inject_nan_at);
  sum.particles = drop.particles();
  const Real t_end = snap_to_grid(s.core.t_end, s.diagnostics_every);
  const Real frame_every = s.core.output_every > 0 ? s.core.output_every : t_end;

  AtomicCsv csv(s.core.out / "diagnostics.csv",
                {"t", "kinetic_energy", "internal_energy", "potential_energy", "psi_energy", "total_energy",
                 "momentum_x", "momentum_y", "mean_abs_div_v", "max_rel_density_error", "semi_axis_x", "semi_axis_y",
                 "semi_axis_x_exact", "semi_axis_y_exact", "semi_axis_error", "rhs_evals", "steps"});
  ResumableVtkSeries vtk(s.core.out, "drop");
  LoopState ls;
  ls.prev_exact_a = drop.config.radius;
  ls.next_checkpoint = s.checkpoint_every;
  auto binds = ls.bind(sum);
  std::vector<Real> y = drop.y0;
  Real t = 0;
  StepperOptions opts = stepper_options(s, drop);
  if (s.restart) {
    const Checkpoint& c = *s.restart;
    if (auto why = layout_mismatch(c, layout)) throw std::runtime_error("--restart: " + *why);
    y = c.y;
    t = c.t;
    for (auto& [name, ptr] : binds) *ptr = c.scalar(name);
    csv.restore(c.text("diagnostics.csv"));
    vtk.restore(c.text("frames"));
    opts.initial_dt = c.last_dt;
    opts.resume_data = c.stepper_data;
  }
  // A blow-up ends the run instead of shrinking steps forever: steps below 1e-6 of the initial
  // stable step are refused.
  opts.min_dt = 1e-6 * drop.model->system().max_stable_dt(0.0, drop.y0.data());
  if (!std::isfinite(opts.min_dt)) opts.min_dt = 0;
  auto stepper = make_stepper(sys, opts, t, y.data());
  const auto stats = [&] { return ls.total(stepper->stats()); };
  const auto save = [&](Real time) {
    Checkpoint c;
    c.program = "water_drop";
    c.argv = s.argv;
    c.particles = layout.particles();
    c.fields = describe_layout(layout);
    c.t = time;
    c.last_dt = stepper->stats().last_dt > 0 ? stepper->stats().last_dt : opts.initial_dt;
    for (auto& [name, ptr] : binds) c.set_scalar(name, *ptr);
    const StepperStats tot = stats();  // counts so far (the restart's base)
    c.set_scalar("steps", tot.steps);
    c.set_scalar("attempts", tot.attempts);
    c.set_scalar("rhs_evals", tot.rhs_evals);
    c.set_scalar("error_test_failures", tot.error_test_failures);
    c.set_scalar("rhs_recoveries", tot.rhs_recoveries);
    c.set_text("run", s.label);
    c.set_text("scene", scene_text(s.scene));
    c.set_text("diagnostics.csv", csv.text());
    c.set_text("frames", vtk.text());
    c.y = y;
    c.stepper_data = stepper->resume_data();
    csv.flush();
    sum.checkpoint = s.core.out / "checkpoint.bin";
    save_checkpoint(sum.checkpoint, c);
  };
  FrameBuffers buf;
  ProgressReporter progress(t, t_end, 2.0);
  const auto start = std::chrono::steady_clock::now();

  const auto record = [&](Real time) {
    const WcsphDiagnostics<2> d = drop.model->diagnostics(time, y.data());
    const SemiAxes ax = measure_semi_axes(y.data() + layout.offset(Field::Position), drop.particles());
    const EllipticDropState ex = drop.exact.at(time);
    const Real err_x = std::abs(ax.x - ex.a) / ex.a, err_y = std::abs(ax.y - ex.b) / ex.b;
    const Real err = std::max(err_x, err_y);
    if (err > sum.max_semi_axis_error) {
      sum.max_semi_axis_error = err;
      sum.time_of_max_error = time;
    }
    // first squeeze: the exact a(t) stops decreasing
    if (ls.squeeze_seen == 0 && ex.a > ls.prev_exact_a && time > 0) {
      ls.squeeze_seen = 1;
      sum.squeeze_error = ls.prev_err_x;
    }
    ls.prev_exact_a = ex.a;
    ls.prev_err_x = err_x;
    if (ls.sample == 0) ls.e0 = d.total_energy;
    if (ls.sample > 0) ls.div_integral += 0.5 * (d.mean_abs_div_v + ls.div_prev) * (time - ls.t_prev);
    ls.t_prev = time;
    ls.div_prev = d.mean_abs_div_v;
    sum.max_rel_density_error = std::max(sum.max_rel_density_error, d.max_rel_density_error);
    sum.kinetic_energy_end = d.kinetic_energy;
    sum.total_energy_drift = (d.total_energy - ls.e0) / ls.e0;
    const StepperStats st = stats();
    csv.row({time, d.kinetic_energy, d.internal_energy, d.potential_energy, d.psi_energy, d.total_energy,
             d.momentum.x(), d.momentum.y(), d.mean_abs_div_v, d.max_rel_density_error, ax.x, ax.y, ex.a, ex.b, err,
             static_cast<Real>(st.rhs_evals), static_cast<Real>(st.steps)});
    if (time >= ls.next_frame - 1e-12 * t_end) {
      sum.last_frame = vtk.write(make_frame(drop, y.data(), buf), time);
      csv.flush();
      ls.next_frame += frame_every;
    }
    ls.sample += 1;
  };

  if (!s.restart) record(0.0);
  sum.ok = true;
  while (t < t_end * (1 - 1e-12)) {
    if (const int sig = stop_requested()) {  // SIGINT/SIGTERM: checkpoint the last recorded state
      sum.stopped_by_signal = sig;
      save(t);
      break;
    }
    const Real t_out = std::min(t_end, ls.sample * s.diagnostics_every);
    const AdvanceStatus st = stepper->advance(t_out, y.data(), t);
    if (st == AdvanceStatus::Failed) {  // y, t: the last good state
      sum.ok = false;
      sum.failure = stepper->failure_reason();
      drop.model->diagnostics(t, y.data());  // pressure and div_v of this state for the frame
      sum.last_frame = vtk.write(make_frame(drop, y.data(), buf), t);
      save(t);
      break;
    }
    record(t);
    if (s.checkpoint_every > 0 && t >= ls.next_checkpoint - 1e-12 * t_end) {
      while (ls.next_checkpoint <= t + 1e-12 * t_end) ls.next_checkpoint += s.checkpoint_every;
      save(t);
    }
    if (!s.quiet) progress.update(t, stats().steps, stepper->stats().last_dt);
  }
  if (!s.quiet) progress.finish();
  if (sum.ok && !sum.stopped_by_signal) {
    csv.flush();
    if (s.checkpoint_every > 0) save(t);
  }
  sum.t_reached = t;
  sum.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  sum.stats = stats();
  sum.mean_abs_div_v_time_avg = t > 0 ? ls.div_integral / t : 0;
  sum.neighbour_builds = drop.model->neighbour_builds();
  return sum;
}

}  // namespace sphark
