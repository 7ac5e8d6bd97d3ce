#include "sphark/scenes/gravitating_sphere/gravitating_sphere_run.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>

#include "sphark/analytic/free_fall.hpp"

namespace sphark {

const std::vector<Real> kSphereFractions = {0.1, 0.5, 0.9};

namespace {
const Real kUniformFreeFall = free_fall_time(3 / (4 * kPi));  // t_ff of the uniform sphere, G = M = R = 1
}  // namespace

std::vector<Real> sphere_lagrangian_radii(const SpmhdScheme<3>& s, const Real* y) {
  const StateLayout& L = s.layout();
  const std::size_t n = s.particles(), ns = s.sinks();
  if (ns == 0) return lagrangian_radii(y + L.offset(Field::Position), n, kSphereFractions);
  std::vector<Real> x(y + L.offset(Field::Position), y + L.offset(Field::Position) + 3 * n);
  x.insert(x.end(), y + L.offset(Species::Sink, Field::Position), y + L.offset(Species::Sink, Field::Position) + 3 * ns);
  std::vector<Real> m = s.masses();
  m.insert(m.end(), y + L.offset(Species::Sink, Field::Mass), y + L.offset(Species::Sink, Field::Mass) + ns);
  return lagrangian_radii(x.data(), m.data(), n + ns, kSphereFractions);
}

GravitatingSphereRun::GravitatingSphereRun(const GravitatingSphereParams& p, Real diagnostics_every)
    : p_(p), sphere_(p), every_(diagnostics_every), sinks_(gravitating_sphere_sink_params(p)) {
  r0_ = sphere_lagrangian_radii(sphere_.scheme, sphere_.y0.data());
}

std::vector<std::string> GravitatingSphereRun::columns() const {
  std::vector<std::string> c = {"t", "kinetic_energy", "thermal_energy", "potential_energy", "total_energy",
                                "momentum_x", "momentum_y", "momentum_z", "angular_momentum_z", "max_density",
                                "lagrangian_radius_10", "lagrangian_radius_50", "lagrangian_radius_90",
                                "free_fall_radius_10", "free_fall_radius_50", "free_fall_radius_90"};
  for (const std::string& s : SinkRunSupport::columns()) c.push_back(s);
  c.push_back("rhs_evals");
  c.push_back("steps");
  return c;
}

std::vector<Real> GravitatingSphereRun::diagnostics(Real t, const Real* y, const StepperStats& st) {
  SpmhdScheme<3>& s = sphere_.scheme;
  const SpmhdDiagnostics d = spmhd_diagnostics(s, t, y);
  Real rho_max = 0;
  for (std::size_t a = 0; a < s.particles(); ++a) rho_max = std::max(rho_max, s.rho()[a]);
  const std::vector<Real> r = sphere_lagrangian_radii(s, y);
  std::vector<Real> row = {t, d.kinetic_energy, d.thermal_energy, d.potential_energy, d.total_energy,
                           d.momentum[0], d.momentum[1], d.momentum[2], angular_momentum_z(s, y), rho_max,
                           r[0], r[1], r[2]};
  // the exact pressureless free fall of each shell from its initial radius (uniform profile)
  for (std::size_t k = 0; k < kSphereFractions.size(); ++k)
    row.push_back(p_.profile == "uniform" && t < kUniformFreeFall
                      ? FreeFallShell(r0_[k], kSphereFractions[k]).radius(t)
                      : std::numeric_limits<Real>::quiet_NaN());
  for (Real v : SinkRunSupport::values(s, y)) row.push_back(v);
  row.push_back(static_cast<Real>(st.rhs_evals));
  row.push_back(static_cast<Real>(st.steps));
  return row;
}

void GravitatingSphereRun::settings(TimeLoopSettings& s) {
  s.sample_every = every_;
  s.frames_basename = "sphere";
  s.progress_interval = 10;
}

std::vector<std::pair<std::string, Real*>> GravitatingSphereRun::saved_numbers() {
  if (!p_.sinks) return {};
  return sinks_.saved_numbers();
}

std::optional<TimeLoopHooks::Resize> GravitatingSphereRun::after_step(Real t, const Real* y,
                                                                    const TimeLoopHooks::CarriedData&) {
  std::optional<TimeLoopHooks::Resize> r = sinks_.after_step(sphere_.scheme, t, y);
  announce_creation(t);
  return r;
}

std::optional<TimeLoopHooks::Resize> GravitatingSphereRun::remove_active(Real t, const Real* y,
                                                                       const std::vector<std::size_t>& active) {
  std::optional<TimeLoopHooks::Resize> r = sinks_.remove_active(sphere_.scheme, t, y, active);
  announce_creation(t);
  return r;
}

void GravitatingSphereRun::announce_creation(Real t) const {
  if (sinks_.created())
    std::fprintf(stderr, "gravitating_sphere: sink %ld created at t = %.5g t_ff (%zu gas particles left)\n",
                 sinks_.log().creations, t / kUniformFreeFall, sphere_.scheme.particles());
}

bool GravitatingSphereRun::finished(Real t) {
  if (!sinks_.log().gas_exhausted) return false;
  std::fprintf(stderr, "gravitating_sphere: the sinks would take every gas particle: the run ends at t = %.6g (%.5g t_ff)\n",
               t, t / kUniformFreeFall);
  return true;
}

StateLayout GravitatingSphereRun::restart_layout(const Checkpoint& c) {
  return SinkRunSupport::restart_layout(sphere_.scheme, c);
}

}  // namespace sphark
