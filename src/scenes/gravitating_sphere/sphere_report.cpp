// The gravitating sphere's summary (summary.csv) from the whole diagnostics table, and its charts.
#include <cmath>
#include <cstdio>
#include <sstream>

#include "sphark/io/csv_writer.hpp"
#include "sphark/io/visualise.hpp"
#include "sphark/scenes/gravitating_sphere/gravitating_sphere_scene.hpp"

namespace sphark {

namespace {
struct Peak {
  Real value = -std::numeric_limits<Real>::infinity(), t = 0;
};
Peak peak_of(const std::vector<Real>& t, const std::vector<Real>& v, Real sign = 1) {
  Peak p;
  for (std::size_t k = 0; k < v.size(); ++k)
    if (sign * v[k] > p.value) p = {sign * v[k], t[k]};
  p.value *= sign;
  return p;
}
// max over rows of |a - b| / b where b is finite (the exact radii end at t_ff)
Real max_relative_error(const std::vector<Real>& a, const std::vector<Real>& b) {
  Real e = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (std::isfinite(b[k]) && b[k] > 0) e = std::max(e, std::abs(a[k] - b[k]) / b[k]);
  return e;
}
}  // namespace

int GravitatingSphereScene::report(const CoreOptions& core, const std::vector<std::string>& runs, bool) {
  if (results_.empty()) return 0;
  const std::string& csv = results_.front().diagnostics;
  const std::vector<Real> t = csv_column(csv, "t"), e = csv_column(csv, "total_energy");
  if (t.empty()) return 0;
  Real drift = 0;
  for (Real v : e) drift = std::max(drift, std::abs(v - e.front()) / std::abs(e.front()));
  std::ostringstream s;
  s << "sphere,particles,t_end,max_energy_error,lagrangian_error_10,lagrangian_error_50,lagrangian_error_90,"
       "kinetic_peak,kinetic_peak_t,thermal_peak,thermal_peak_t,potential_min,potential_min_t,steps,rhs_evals,wall_s\n";
  char line[512];
  Real err[3];
  for (int k = 0; k < 3; ++k) {
    const char* f = k == 0 ? "10" : k == 1 ? "50" : "90";
    err[k] = max_relative_error(csv_column(csv, std::string("lagrangian_radius_") + f),
                                csv_column(csv, std::string("free_fall_radius_") + f));
  }
  const Peak ke = peak_of(t, csv_column(csv, "kinetic_energy")), te = peak_of(t, csv_column(csv, "thermal_energy"));
  const Peak pe = peak_of(t, csv_column(csv, "potential_energy"), -1);
  const TimeLoopResult& r = results_.front();
  std::snprintf(line, sizeof line, "%s,%zu,%.6g,%.4e,%.4e,%.4e,%.4e,%.6g,%.4g,%.6g,%.4g,%.6g,%.4g,%ld,%ld,%.1f\n",
                runs.front().c_str(), params_.particles, t.back(), drift, err[0], err[1], err[2], ke.value, ke.t,
                te.value, te.t, pe.value, pe.t, r.stats.steps, r.stats.rhs_evals, r.wall_seconds);
  s << line;
  std::printf("%s", s.str().c_str());
  write_file_atomically(core.out / "summary.csv", s.str());
  if (core.render)
    run_python("gravitating_sphere.py", {"--dir", (core.out / runs.front()).string(), "--sphere", runs.front()}, false);
  return 0;
}

}  // namespace sphark
