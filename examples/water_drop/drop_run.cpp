#include "drop_run.hpp"

#include <chrono>
#include <cmath>
#include <iostream>

#include "sphark/integrate/stepper.hpp"
#include "sphark/io/csv_writer.hpp"
#include "sphark/io/progress.hpp"
#include "sphark/io/vtk_series.hpp"

namespace sphark {

std::vector<Real> drop_absolute_tolerances(const WaterDrop& drop, Real atol) {
  const WaterDropConfig& c = drop.config;
  const Real vscale = c.amplitude * c.radius > 0 ? c.amplitude * c.radius : c.omega * c.radius;
  return per_field_tolerance(drop.model->layout(),
                             {{Field::Position, atol * c.radius},
                              {Field::Velocity, atol * vscale},
                              {Field::Density, atol * c.rho0},
                              {Field::Psi, atol * c.rho0 * c.sound_speed * vscale}},
                             atol);
}

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
  o.atol = drop_absolute_tolerances(drop, s.core.atol);
  o.fixed_dt = s.core.dt;
  return o;
}
}  // namespace

DropRunSummary run_water_drop(const DropRunSettings& s) {
  DropRunSummary sum;
  WaterDrop drop = make_water_drop(s.scene);
  OdeSystem& sys = drop.model->system();
  sum.particles = drop.particles();
  std::vector<Real> y = drop.y0;
  auto stepper = make_stepper(sys, stepper_options(s, drop), 0.0, y.data());

  CsvWriter csv(s.core.out / "diagnostics.csv",
                {"t", "kinetic_energy", "internal_energy", "potential_energy", "psi_energy", "total_energy",
                 "momentum_x", "momentum_y", "mean_abs_div_v", "max_rel_density_error", "semi_axis_x", "semi_axis_y",
                 "semi_axis_x_exact", "semi_axis_y_exact", "semi_axis_error", "rhs_evals", "steps"});
  VtkSeriesWriter vtk(s.core.out, "drop");
  FrameBuffers buf;
  ProgressReporter progress(0.0, s.core.t_end, 2.0);
  const auto start = std::chrono::steady_clock::now();

  Real t = 0, e0 = 0, div_integral = 0, t_prev = 0, div_prev = 0;
  bool squeeze_seen = false;
  Real prev_exact_a = drop.config.radius, prev_err_x = 0;
  const Real frame_every = s.core.output_every > 0 ? s.core.output_every : s.core.t_end;
  Real next_frame = 0;
  long sample = 0;
  const auto record = [&](Real time) {
    const WcsphDiagnostics<2> d = drop.model->diagnostics(time, y.data());
    const SemiAxes ax = measure_semi_axes(y.data() + drop.model->layout().offset(Field::Position), drop.particles());
    const EllipticDropState ex = drop.exact.at(time);
    const Real err_x = std::abs(ax.x - ex.a) / ex.a, err_y = std::abs(ax.y - ex.b) / ex.b;
    const Real err = std::max(err_x, err_y);
    if (err > sum.max_semi_axis_error) {
      sum.max_semi_axis_error = err;
      sum.time_of_max_error = time;
    }
    // first squeeze: the exact a(t) stops decreasing
    if (!squeeze_seen && ex.a > prev_exact_a && time > 0) {
      squeeze_seen = true;
      sum.squeeze_error = prev_err_x;
    }
    prev_exact_a = ex.a;
    prev_err_x = err_x;
    if (sample == 0) e0 = d.total_energy;
    if (sample > 0) div_integral += 0.5 * (d.mean_abs_div_v + div_prev) * (time - t_prev);
    t_prev = time;
    div_prev = d.mean_abs_div_v;
    sum.max_rel_density_error = std::max(sum.max_rel_density_error, d.max_rel_density_error);
    sum.kinetic_energy_end = d.kinetic_energy;
    sum.total_energy_drift = (d.total_energy - e0) / e0;
    const StepperStats st = stepper->stats();
    csv.row({time, d.kinetic_energy, d.internal_energy, d.potential_energy, d.psi_energy, d.total_energy,
             d.momentum.x(), d.momentum.y(), d.mean_abs_div_v, d.max_rel_density_error, ax.x, ax.y, ex.a, ex.b, err,
             static_cast<Real>(st.rhs_evals), static_cast<Real>(st.steps)});
    if (time >= next_frame - 1e-12 * s.core.t_end) {
      vtk.write(make_frame(drop, y.data(), buf), time);
      next_frame += frame_every;
    }
    ++sample;
  };

  record(0.0);
  sum.ok = true;
  while (t < s.core.t_end * (1 - 1e-12)) {
    const Real t_out = std::min(s.core.t_end, (sample)*s.diagnostics_every);
    const AdvanceStatus st = stepper->advance(t_out, y.data(), t);
    if (st == AdvanceStatus::Failed) {
      sum.ok = false;
      sum.failure = stepper->failure_reason();
      vtk.write(make_frame(drop, y.data(), buf), t);  // the last good state, for inspection
      break;
    }
    record(t);
    if (!s.quiet) progress.update(t, stepper->stats().steps, stepper->stats().last_dt);
  }
  if (!s.quiet) progress.finish();
  sum.t_reached = t;
  sum.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  sum.stats = stepper->stats();
  sum.mean_abs_div_v_time_avg = t > 0 ? div_integral / t : 0;
  sum.neighbour_builds = drop.model->neighbour_builds();
  return sum;
}

}  // namespace sphark
