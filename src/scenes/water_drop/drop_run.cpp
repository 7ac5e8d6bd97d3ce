#include "drop_run.hpp"

#include <cmath>

#include "sphark/run/migration_step.hpp"
#include "sphark/run/restart.hpp"

namespace sphark {

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

DropRun::DropRun(const WaterDropConfig& config, Real diagnostics_every, Real frame_every, Communicator world)
    : world_(std::move(world)), diagnostics_every_(diagnostics_every), frame_every_(frame_every) {
  if (world_.distributed()) {
    dist_ = std::make_unique<DistributedDrop>(config, world_);
    drop_ = &dist_->drop();
    sum_.particles = dist_->global_particles();
  } else {
    serial_.emplace(make_water_drop(config));
    drop_ = &*serial_;
    sum_.particles = drop_->particles();
  }
  prev_exact_a_ = config.radius;
}

StepperOptions DropRun::stepper(const CoreOptions& core, std::string_view program) {
  StepperOptions o = stepper_options(core, system(), program);
  o.atol = water_drop_absolute_tolerances(*drop_, core.atol);  // one scale per field
  o.communicator = world_;
  atol_ = core.atol;
  return o;
}

std::vector<std::string> DropRun::columns() const {
  return {"t", "kinetic_energy", "internal_energy", "potential_energy", "psi_energy", "total_energy",
          "momentum_x", "momentum_y", "mean_abs_div_v", "max_rel_density_error", "semi_axis_x", "semi_axis_y",
          "semi_axis_x_exact", "semi_axis_y_exact", "semi_axis_error", "rhs_evals", "steps"};
}

std::vector<Real> DropRun::diagnostics(Real time, const Real* y, const StepperStats& st) {
  const std::size_t n = drop_->particles();
  const WcsphDiagnostics<2> d =
      dist_ ? reduce_diagnostics(world_, drop_->model->diagnostics(time, y), n) : drop_->model->diagnostics(time, y);
  const SemiAxes ax = measure_semi_axes(world_, y + layout().offset(Field::Position), n);
  const EllipticDropState ex = drop_->exact.at(time);
  const Real err_x = std::abs(ax.x - ex.a) / ex.a, err_y = std::abs(ax.y - ex.b) / ex.b;
  const Real err = std::max(err_x, err_y);
  if (err > sum_.max_semi_axis_error) {
    sum_.max_semi_axis_error = err;
    sum_.time_of_max_error = time;
  }
  if (squeeze_seen_ == 0 && ex.a > prev_exact_a_ && time > 0) {  // first squeeze: a(t) stops decreasing
    squeeze_seen_ = 1;
    sum_.squeeze_error = prev_err_x_;
  }
  prev_exact_a_ = ex.a;
  prev_err_x_ = err_x;
  if (samples_ == 0) e0_ = d.total_energy;
  if (samples_ > 0) div_integral_ += 0.5 * (d.mean_abs_div_v + div_prev_) * (time - t_prev_);
  t_prev_ = time;
  div_prev_ = d.mean_abs_div_v;
  samples_ += 1;
  sum_.max_rel_density_error = std::max(sum_.max_rel_density_error, d.max_rel_density_error);
  sum_.kinetic_energy_end = d.kinetic_energy;
  sum_.total_energy_drift = (d.total_energy - e0_) / e0_;
  return {time, d.kinetic_energy, d.internal_energy, d.potential_energy, d.psi_energy, d.total_energy, d.momentum.x(),
          d.momentum.y(), d.mean_abs_div_v, d.max_rel_density_error, ax.x, ax.y, ex.a, ex.b, err,
          static_cast<Real>(st.rhs_evals), static_cast<Real>(st.steps)};
}

std::vector<std::pair<std::string, Real*>> DropRun::saved_numbers() {
  return {{"samples", &samples_}, {"e0", &e0_}, {"div_integral", &div_integral_}, {"t_prev", &t_prev_},
          {"div_prev", &div_prev_}, {"prev_exact_a", &prev_exact_a_}, {"prev_err_x", &prev_err_x_},
          {"squeeze_seen", &squeeze_seen_},
          {"max_semi_axis_error", &sum_.max_semi_axis_error}, {"time_of_max_error", &sum_.time_of_max_error},
          {"squeeze_error", &sum_.squeeze_error}, {"max_rel_density_error", &sum_.max_rel_density_error},
          {"kinetic_energy_end", &sum_.kinetic_energy_end}, {"total_energy_drift", &sum_.total_energy_drift}};
}

void DropRun::settings(TimeLoopSettings& s) {
  s.sample_every = diagnostics_every_;
  s.frames_basename = "drop";
  s.frame_every = frame_every_;
}

ParticleFrame DropRun::frame(Real t, const Real* y) {
  ParticleFrame f = drop_->model->frame(t, y);
  if (dist_) f.ids = dist_->ids().data();  // parallel VTK: each particle's global id
  return f;
}

// This rank's particles to their owners (run/migration_step.hpp); the loop continues from the new state.
std::optional<TimeLoopHooks::Resize> DropRun::after_step(Real, const Real* y, const TimeLoopHooks::CarriedData& carried) {
  if (!dist_) return std::nullopt;
  return migration_step(
      schedule_, world_, layout(), y, carried,
      [&](std::vector<Real>& state, std::vector<Real>* kick, bool repartition) {
        dist_->migrate(state, kick, repartition);
        return layout();
      },
      [&] { return water_drop_absolute_tolerances(*drop_, atol_); });
}

std::vector<std::int64_t> DropRun::global_ids() const {
  if (!dist_) return SceneRun::global_ids();
  return dist_->ids();
}

std::vector<std::int64_t> DropRun::take_share(const Checkpoint& c) {
  if (!dist_) return SceneRun::take_share(c);
  schedule_.steps = static_cast<long>(c.scalar("steps"));  // the migration schedule continues
  return dist_->take_share(c.y);
}

DropRunSummary DropRun::summary(const TimeLoopResult& result) const {
  DropRunSummary s = sum_;
  s.loop = result;
  s.mean_abs_div_v_time_avg = result.t_reached > 0 ? div_integral_ / result.t_reached : 0;
  s.neighbour_builds = drop_->model->neighbour_builds();
  return s;
}

}  // namespace sphark
