#include "drop_run.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "sphark/run/restart.hpp"

namespace sphark {

namespace {
// Point arrays of one frame; the vectors must outlive the write() call.
struct FrameBuffers {
  std::vector<Real> velocity, density, pressure, div_v, psi;
};

ParticleFrame make_frame(WaterDrop& drop, Real t, const Real* y, FrameBuffers& buf) {
  const StateLayout& L = drop.model->layout();
  const std::size_t n = L.particles();
  const Real* v = y + L.offset(Field::Velocity);
  buf.velocity.assign(v, v + 2 * n);
  const Real* rho = y + L.offset(Field::Density);
  buf.density.assign(rho, rho + n);
  buf.pressure = drop.model->pressure(t, y);
  buf.div_v = drop.model->div_v(t, y);
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

// The numbers of the accuracy summary accumulated sample by sample (saved in checkpoints).
struct Accumulators {
  Real samples = 0, e0 = 0, div_integral = 0, t_prev = 0, div_prev = 0, prev_exact_a = 0, prev_err_x = 0,
       squeeze_seen = 0;
  std::vector<std::pair<std::string, Real*>> bind(DropRunSummary& sum) {
    return {{"samples", &samples}, {"e0", &e0}, {"div_integral", &div_integral}, {"t_prev", &t_prev},
            {"div_prev", &div_prev}, {"prev_exact_a", &prev_exact_a}, {"prev_err_x", &prev_err_x},
            {"squeeze_seen", &squeeze_seen},
            {"max_semi_axis_error", &sum.max_semi_axis_error}, {"time_of_max_error", &sum.time_of_max_error},
            {"squeeze_error", &sum.squeeze_error}, {"max_rel_density_error", &sum.max_rel_density_error},
            {"kinetic_energy_end", &sum.kinetic_energy_end}, {"total_energy_drift", &sum.total_energy_drift}};
  }
};
}  // namespace

std::string scene_text(const WaterDropConfig& c) {
  std::string s;
  const auto put = [&s](const char* key, Real v) { append_key_value(s, key, v); };
  put("radius", c.radius);
  put("spacing", c.spacing);
  put("amplitude", c.amplitude);
  put("omega", c.omega);
  put("rho0", c.rho0);
  put("sound_speed", c.sound_speed);
  put("h_factor", c.h_factor);
  append_key_value(s, "kernel", c.kernel);
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
  sum.particles = drop.particles();

  TimeLoopSettings ts;
  ts.program = "water_drop";
  ts.run = s.label;
  ts.argv = s.argv;
  ts.texts = {{"scene", scene_text(s.scene)}};
  ts.t_end = s.core.t_end;
  ts.sample_every = s.diagnostics_every;
  ts.diagnostics_csv = s.core.out / "diagnostics.csv";
  ts.columns = {"t", "kinetic_energy", "internal_energy", "potential_energy", "psi_energy", "total_energy",
                "momentum_x", "momentum_y", "mean_abs_div_v", "max_rel_density_error", "semi_axis_x", "semi_axis_y",
                "semi_axis_x_exact", "semi_axis_y_exact", "semi_axis_error", "rhs_evals", "steps"};
  ts.frames_dir = s.core.out;
  ts.frames_basename = "drop";
  ts.frame_every = s.core.output_every;
  ts.checkpoint = s.core.out / "checkpoint.bin";
  ts.checkpoint_every = s.checkpoint_every;
  ts.restart = s.restart;
  ts.inject_nan_at = s.inject_nan_at;
  ts.quiet = s.quiet;

  Accumulators acc;
  acc.prev_exact_a = drop.config.radius;
  FrameBuffers buf;
  TimeLoopHooks hooks;
  hooks.state = acc.bind(sum);
  hooks.diagnostics = [&](Real time, const Real* y, const StepperStats& st) {
    const WcsphDiagnostics<2> d = drop.model->diagnostics(time, y);
    const SemiAxes ax = measure_semi_axes(y + layout.offset(Field::Position), drop.particles());
    const EllipticDropState ex = drop.exact.at(time);
    const Real err_x = std::abs(ax.x - ex.a) / ex.a, err_y = std::abs(ax.y - ex.b) / ex.b;
    const Real err = std::max(err_x, err_y);
    if (err > sum.max_semi_axis_error) {
      sum.max_semi_axis_error = err;
      sum.time_of_max_error = time;
    }
    // first squeeze: the exact a(t) stops decreasing
    if (acc.squeeze_seen == 0 && ex.a > acc.prev_exact_a && time > 0) {
      acc.squeeze_seen = 1;
      sum.squeeze_error = acc.prev_err_x;
    }
    acc.prev_exact_a = ex.a;
    acc.prev_err_x = err_x;
    if (acc.samples == 0) acc.e0 = d.total_energy;
    if (acc.samples > 0) acc.div_integral += 0.5 * (d.mean_abs_div_v + acc.div_prev) * (time - acc.t_prev);
    acc.t_prev = time;
    acc.div_prev = d.mean_abs_div_v;
    acc.samples += 1;
    sum.max_rel_density_error = std::max(sum.max_rel_density_error, d.max_rel_density_error);
    sum.kinetic_energy_end = d.kinetic_energy;
    sum.total_energy_drift = (d.total_energy - acc.e0) / acc.e0;
    return std::vector<Real>{time, d.kinetic_energy, d.internal_energy, d.potential_energy, d.psi_energy,
                             d.total_energy, d.momentum.x(), d.momentum.y(), d.mean_abs_div_v,
                             d.max_rel_density_error, ax.x, ax.y, ex.a, ex.b, err, static_cast<Real>(st.rhs_evals),
                             static_cast<Real>(st.steps)};
  };
  // pressure and div_v of the frame: from diagnostics() at the same state, just before
  hooks.frame = [&](Real t, const Real* y) { return make_frame(drop, t, y, buf); };

  sum.loop = run_time_loop(drop.model->system(), layout, stepper_options(s, drop), drop.y0, ts, hooks);
  const Real t = sum.loop.t_reached;
  sum.mean_abs_div_v_time_avg = t > 0 ? acc.div_integral / t : 0;
  sum.neighbour_builds = drop.model->neighbour_builds();
  return sum;
}

}  // namespace sphark
