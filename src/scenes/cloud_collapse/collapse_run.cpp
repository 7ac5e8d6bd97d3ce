#include "collapse_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <numeric>
#include <sstream>

#include "sphark/diagnostics/column_density.hpp"
#include "sphark/diagnostics/step_levels.hpp"
#include "sphark/io/atomic_file.hpp"
#include "sphark/run/signals.hpp"

namespace sphark {

namespace {
constexpr Real kNaN = std::numeric_limits<Real>::quiet_NaN();

Real minimum(const std::vector<Real>& v) {
  Real m = std::numeric_limits<Real>::infinity();
  for (Real x : v) m = std::min(m, x);
  return m;
}

}  // namespace

CollapseRun::CollapseRun(const CloudCollapseParams& p, Real diagnostics_every)
    : p_(p), cloud_(p), every_(diagnostics_every), sinks_(cloud_.sinks) {}

std::vector<std::string> CollapseRun::columns() const {
  return {"t", "t_over_tff", "max_density", "mean_h_divB_over_B", "max_h_divB_over_B", "momentum_magnitude",
          "kinetic_energy", "magnetic_energy", "thermal_energy", "psi_energy", "potential_energy", "total_energy",
          "n_sinks", "sink_mass", "sink_x", "sink_y", "sink_z", "angular_momentum_z", "momentum_rate",
          "tensile_momentum_rate", "other_momentum_rate", "dt_courant", "dt_force", "gas_particles", "steps",
          "rhs_evals", "particle_evals", "particles_at_h_max"};
}

std::vector<Real> CollapseRun::diagnostics(Real t, const Real* y, const StepperStats& st) {
  SpmhdScheme<3>& s = cloud_.scheme;
  const SpmhdDiagnostics d = spmhd_diagnostics(s, t, y);
  const SpmhdScheme<3>::MomentumBudget budget = s.momentum_budget(t, y);
  std::vector<Real> courant, force;
  const bool steps_ok = s.stable_steps(t, y, nullptr, courant, force) == 0;
  const Real rho_max = s.rho().empty() ? kNaN : *std::max_element(s.rho().begin(), s.rho().end());
  const StateLayout& L = s.layout();
  const std::size_t ns = s.sinks();
  const Real* xs = ns ? y + L.offset(Species::Sink, Field::Position) : nullptr;
  const std::array<Real, 2> sink = SinkRunSupport::values(s, y);
  const Vec<3> p(d.momentum[0], d.momentum[1], d.momentum[2]);
  return {t, t / cloud_.numbers.free_fall_time, rho_max * cloud_.units.density_g_cm3(), d.mean_h_divb_over_b,
          d.max_h_divb_over_b, p.norm(), d.kinetic_energy, d.magnetic_energy, d.thermal_energy, d.psi_energy,
          d.potential_energy, d.total_energy, sink[0], sink[1],
          ns ? xs[0] : kNaN, ns ? xs[1] : kNaN, ns ? xs[2] : kNaN, angular_momentum_z(s, y), budget.total.norm(),
          budget.tensile.norm(), (budget.total - budget.tensile).norm(), steps_ok ? minimum(courant) : kNaN,
          steps_ok ? minimum(force) : kNaN, static_cast<Real>(s.particles()), static_cast<Real>(st.steps),
          static_cast<Real>(st.rhs_evals), static_cast<Real>(st.particle_evals),
          static_cast<Real>(s.smoothing_lengths_at_cap())};
}

ParticleFrame CollapseRun::frame(Real t, const Real* y) {
  last_frame_y_.assign(y, y + cloud_.scheme.size());
  last_frame_t_ = t;
  return frame_.build(cloud_.scheme, t, y, &cloud_.box);
}

std::vector<std::pair<std::string, Real*>> CollapseRun::saved_numbers() {
  return sinks_.saved_numbers();
}

void CollapseRun::settings(TimeLoopSettings& s) {
  s.sample_every = every_;
  s.frames_basename = "collapse";
  s.progress_interval = 10;
  s.step_floor_fraction = p_.step_floor_tff * cloud_.numbers.free_fall_time / s.t_end;
  dir_ = s.frames_dir;
}

std::optional<TimeLoopHooks::Resize> CollapseRun::after_step(Real t, const Real* y,
                                                           const TimeLoopHooks::CarriedData&) {
  std::optional<TimeLoopHooks::Resize> r = sinks_.after_step(cloud_.scheme, t, y);
  announce_creation(t, r);
  return r;
}

std::optional<TimeLoopHooks::Resize> CollapseRun::remove_active(Real t, const Real* y,
                                                              const std::vector<std::size_t>& active) {
  std::optional<TimeLoopHooks::Resize> r = sinks_.remove_active(cloud_.scheme, t, y, active);
  announce_creation(t, r);
  return r;
}

void CollapseRun::announce_creation(Real t, const std::optional<TimeLoopHooks::Resize>& r) {
  if (!sinks_.created() || !r) return;
  std::fprintf(stderr, "cloud_collapse: sink %ld created at t = %.5g t_ff (%zu gas particles left)%s\n",
               sinks_.log().creations, t / cloud_.numbers.free_fall_time, cloud_.scheme.particles(),
               sinks_.log().forced_creations > forced_announced_ ? ", forced past the checks (--force-sink-above)" : "");
  forced_announced_ = sinks_.log().forced_creations;
  write_step_levels("sink_formation", t, r->y.data());
}

StateLayout CollapseRun::restart_layout(const Checkpoint& c) {
  const StateLayout L = SinkRunSupport::restart_layout(cloud_.scheme, c);
  std::ifstream in(dir_ / "step_levels.csv");
  std::ostringstream text;
  text << in.rdbuf();
  levels_csv_ = text.str();
  return L;
}

// step_levels.csv: per event, the gas particles' own stable steps min(Courant, force) on
// power-of-two levels above the smallest (diagnostics/step_levels.hpp).
void CollapseRun::write_step_levels(const std::string& event, Real t, const Real* y) {
  std::vector<Real> courant, force;
  if (cloud_.scheme.stable_steps(t, y, nullptr, courant, force) != 0) return;
  std::vector<Real> dt(courant.size());
  for (std::size_t a = 0; a < dt.size(); ++a) dt[a] = std::min(courant[a], force[a]);
  const StepLevels levels = step_levels(dt);
  if (levels_csv_.empty()) levels_csv_ = "event,t_over_tff,dt_min,level,count,fraction,block_speedup\n";
  const Real n = static_cast<Real>(dt.size());
  char line[256];
  for (std::size_t k = 0; k < levels.count.size(); ++k) {
    std::snprintf(line, sizeof line, "%s,%.6g,%.6e,%zu,%zu,%.6e,%.4f\n", event.c_str(),
                  t / cloud_.numbers.free_fall_time, levels.dt_min, k, levels.count[k],
                  static_cast<Real>(levels.count[k]) / n, levels.speedup());
    levels_csv_ += line;
  }
  write_file_atomically(dir_ / "step_levels.csv", levels_csv_);
}

// Skipped once a stop signal arrived (the process must end within a second).
void CollapseRun::write_final_products() {
  if (last_frame_y_.empty() || dir_.empty() || stop_requested()) return;
  write_step_levels("end", last_frame_t_, last_frame_y_.data());
  if (!stop_requested()) write_maps(last_frame_y_.data());
}

// Column density along y (seed 000, Fig. 4), g/cm^2 over code lengths: the whole cloud (2.5 R
// wide) and a zoom 0.3 R wide on the first sink (or the density maximum without one).
void CollapseRun::write_maps(const Real* y) {
  SpmhdScheme<3>& s = cloud_.scheme;
  if (s.evaluate(last_frame_t_, y) != 0) return;
  const std::size_t n = s.particles();
  std::vector<Real> x(y + s.layout().offset(Field::Position), y + s.layout().offset(Field::Position) + 3 * n);
  cloud_.box.wrap_all(x.data(), n, x.data());
  Vec<3> centre = Vec<3>::Zero();
  if (s.sinks() > 0) {
    centre = Eigen::Map<const Vec<3>>(y + s.layout().offset(Species::Sink, Field::Position));
  } else {
    const auto densest = std::max_element(s.rho().begin(), s.rho().end()) - s.rho().begin();
    centre = Eigen::Map<const Vec<3>>(x.data() + 3 * densest);
  }
  const Real sigma_unit = cloud_.units.mass_g / (cloud_.units.length_cm * cloud_.units.length_cm);
  const Real R = cloud_.numbers.radius;
  struct View {
    const char* file;
    Real cx, cz, half;
  };
  for (const View& v : {View{"column_density_y.csv", 0, 0, 1.25 * R},
                        View{"column_density_y_zoom.csv", centre[0], centre[2], 0.15 * R}}) {
    ColumnDensityMap map;
    try {
      map = column_density(x.data(), s.masses().data(), s.h().data(), n, 1, v.cx - v.half, v.cx + v.half,
                           v.cz - v.half, v.cz + v.half, 256, 256, [] { return stop_requested() != 0; });
    } catch (const ColumnDensityStopped&) {
      return;  // a stop signal: no map rather than a late exit
    }
    for (Real& value : map.sigma) value *= sigma_unit;
    write_column_density((dir_ / v.file).string(), map);
  }
}

}  // namespace sphark
