// The cloud collapse's summary (summary_<variant>.csv) from a run's diagnostics table and last
// frame, and its figures (vis/cloud_collapse.py).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "collapse_run.hpp"
#include "sphark/io/atomic_file.hpp"
#include "sphark/io/visualise.hpp"
#include "sphark/scenes/cloud_collapse/cloud_collapse_scene.hpp"

namespace sphark {

namespace {
struct Peak {
  Real value = -HUGE_VAL, t = std::nan("");
  std::size_t row = 0;
};
Peak peak_of(const std::vector<Real>& t, const std::vector<Real>& v) {
  Peak p;
  for (std::size_t k = 0; k < v.size(); ++k)
    if (v[k] > p.value) p = {v[k], t[k], k};
  return p;
}
Real max_of(const std::vector<Real>& v) {
  Real m = -HUGE_VAL;
  for (Real x : v) m = std::max(m, x);
  return m;
}
// int |rate| dt by the trapezoid rule over the rows: a bound on the momentum the terms other
// than the tensile correction can have changed (they conserve it to round-off).
Real integrated(const std::vector<Real>& t, const std::vector<Real>& rate) {
  Real sum = 0;
  for (std::size_t k = 1; k < t.size(); ++k) sum += 0.5 * (rate[k] + rate[k - 1]) * (t[k] - t[k - 1]);
  return sum;
}
}  // namespace

std::pair<Real, Real> CollapseRun::sink_offset(Real fraction_of_max) {
  SpmhdScheme<3>& s = cloud_.scheme;
  const Real nan = std::nan("");
  if (last_frame_y_.empty() || s.sinks() == 0 || s.evaluate(last_frame_t_, last_frame_y_.data()) != 0) return {nan, nan};
  const StateLayout& L = s.layout();
  const Real* y = last_frame_y_.data();
  const Vec<3> xs = Eigen::Map<const Vec<3>>(y + L.offset(Species::Sink, Field::Position));
  const Vec<3> vs = Eigen::Map<const Vec<3>>(y + L.offset(Species::Sink, Field::Velocity));
  const Real rho_dense = fraction_of_max * *std::max_element(s.rho().begin(), s.rho().end());
  Vec<3> mx = Vec<3>::Zero(), mv = Vec<3>::Zero();
  Real mass = 0;
  for (std::size_t a = 0; a < s.particles(); ++a) {
    if (s.rho()[a] < rho_dense) continue;
    const Real m = s.masses()[a];
    mx += m * (xs + cloud_.box.minimum_image(Eigen::Map<const Vec<3>>(y + L.offset(Field::Position) + 3 * a) - xs));
    mv += m * Eigen::Map<const Vec<3>>(y + L.offset(Field::Velocity) + 3 * a);
    mass += m;
  }
  if (mass == 0) return {nan, nan};
  return {(mx / mass - xs).norm(), (mv / mass - vs).norm()};
}

std::string collapse_summary(const std::string& variant, CollapseRun& run, const TimeLoopResult& result) {
  const std::string& csv = result.diagnostics;
  const std::vector<Real> t = csv_column(csv, "t_over_tff");
  const Peak rho = peak_of(t, csv_column(csv, "max_density"));
  const std::vector<Real> err = csv_column(csv, "mean_h_divB_over_B");
  const Peak momentum = peak_of(t, csv_column(csv, "momentum_magnitude"));
  const Real tff = run.cloud().numbers.free_fall_time;
  const Real other = integrated(csv_column(csv, "t"), csv_column(csv, "other_momentum_rate"));
  const auto [offset, speed] = run.sink_offset(0.01);
  const SinkEventLog& log = run.sink_log();
  std::string refusals;
  for (const auto& [check, count] : log.refusals) {
    if (!refusals.empty()) refusals += ' ';
    refusals += to_string(check);
    refusals += ':';
    refusals += std::to_string(count);
  }
  std::ostringstream s;
  s << "variant,sphere_particles,particles,t_reached_over_tff,sink_time_over_tff,n_sinks,sink_mass,accreted,"
       "peak_density,peak_density_t,mean_h_divB_over_B_at_peak_density,max_mean_h_divB_over_B,peak_momentum,"
       "peak_momentum_t,other_momentum_bound,sink_offset,sink_relative_speed,steps,rhs_evals,particle_evals,wall_s,refusals\n";
  char line[1024];
  const std::vector<Real> sinks = csv_column(csv, "n_sinks"), sink_mass = csv_column(csv, "sink_mass");
  std::snprintf(line, sizeof line,
                "%s,%zu,%zu,%.5g,%.5g,%.0f,%.5g,%ld,%.4e,%.5g,%.4e,%.4e,%.4e,%.5g,%.3e,%.4e,%.4e,%ld,%ld,%ld,%.1f,%s\n",
                variant.c_str(), run.cloud().sphere_particles(),
                run.cloud().sphere_particles() + run.cloud().placement.ambient.size() / 3,
                result.t_reached / tff, log.first_creation_time >= 0 ? log.first_creation_time / tff : std::nan(""),
                sinks.empty() ? 0.0 : sinks.back(), sink_mass.empty() ? 0.0 : sink_mass.back(),
                log.accreted_particles, rho.value, rho.t, err.empty() ? std::nan("") : err[rho.row], max_of(err),
                momentum.value, momentum.t, other, offset, speed, result.stats.steps, result.stats.rhs_evals,
                result.stats.particle_evals, result.wall_seconds, refusals.empty() ? "-" : refusals.c_str());
  s << line;
  return s.str();
}

int CloudCollapseScene::report(const CoreOptions& core, const std::vector<std::string>&, bool) {
  for (const auto& [variant, text] : summaries_) {
    std::printf("%s", text.c_str());
    write_file_atomically(core.out / ("summary_" + subdirectory(variant).string() + ".csv"), text);
  }
  if (core.render && !summaries_.empty())
    run_python("cloud_collapse.py", {"--out", core.out.string()}, false);
  return 0;
}

}  // namespace sphark
