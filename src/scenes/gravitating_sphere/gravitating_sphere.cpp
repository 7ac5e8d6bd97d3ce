#include "sphark/scenes/gravitating_sphere/gravitating_sphere.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "sphark/gravity/kernel_softening.hpp"
#include "sphark/sinks/sink_run.hpp"

namespace sphark {

Real default_u0(const std::string& profile) { return profile == "evrard" ? 0.05 : 1e-4; }

SpmhdOptions gravitating_sphere_options(const GravitatingSphereParams& p) {
  SpmhdOptions o;
  o.gamma = p.gamma;
  o.alpha_visc = p.alpha_visc;
  o.alpha_u = p.alpha_u;
  o.courant = p.courant;
  enable_self_gravity(o, p.gravity, p.theta, p.opening);
  o.force_courant = p.force_courant;
  if (p.sinks) enable_kernel_softened_sinks(o, p.accretion_radius);  // as the cloud collapse
  return o;
}

SinkParams gravitating_sphere_sink_params(const GravitatingSphereParams& p) {
  if (p.sinks && !(p.rho_sink > 0 && p.accretion_radius > 0))
    throw std::invalid_argument("gravitating sphere: sinks need rho_sink > 0 and r_acc > 0");
  SinkParams s;
  s.rho_sink = p.rho_sink;
  s.accretion_radius = p.accretion_radius;
  s.creation_radius = 5 * p.accretion_radius;  // as the cloud collapse (Phantom r_crit)
  s.G = 1;
  s.pair_potential = cubic_spline_pair_potential();
  return s;
}

namespace {
ParticlePlacement place(const GravitatingSphereParams& p) {
  if (p.profile != "uniform" && p.profile != "evrard")
    throw std::invalid_argument("unknown sphere profile '" + p.profile + "' (uniform, evrard)");
  SphereSpec spec;
  spec.particles = p.particles;
  spec.random = p.random;
  return p.profile == "evrard" ? evrard_sphere(spec) : uniform_sphere(spec);
}
}  // namespace

GravitatingSphere::GravitatingSphere(const GravitatingSphereParams& p)
    : placement(place(p)),
      scheme(std::vector<Real>(placement.size(), placement.particle_mass), gravitating_sphere_options(p)),
      y0(scheme.size(), 0) {
  const StateLayout& L = scheme.layout();
  std::copy(placement.x.begin(), placement.x.end(), y0.begin() + static_cast<std::ptrdiff_t>(L.offset(Field::Position)));
  const Real u0 = p.u0 > 0 ? p.u0 : default_u0(p.profile);
  auto u = scalar_field(y0.data(), L, Field::InternalEnergy);
  u.setConstant(u0);
}

std::vector<Real> lagrangian_radii(const Real* x, std::size_t n, const std::vector<Real>& fractions) {
  Vec<3> centre = Vec<3>::Zero();
  for (std::size_t a = 0; a < n; ++a) centre += Eigen::Map<const Vec<3>>(x + 3 * a);
  centre /= static_cast<Real>(n);
  std::vector<Real> r(n);
  for (std::size_t a = 0; a < n; ++a) r[a] = (Eigen::Map<const Vec<3>>(x + 3 * a) - centre).norm();
  std::sort(r.begin(), r.end());
  std::vector<Real> out;
  for (Real f : fractions) {
    const auto k = static_cast<std::size_t>(std::ceil(f * static_cast<Real>(n)));
    out.push_back(r[std::clamp<std::size_t>(k, 1, n) - 1]);
  }
  return out;
}

std::vector<Real> lagrangian_radii(const Real* x, const Real* m, std::size_t n, const std::vector<Real>& fractions) {
  Vec<3> centre = Vec<3>::Zero();
  Real total = 0;
  for (std::size_t a = 0; a < n; ++a) {
    centre += m[a] * Eigen::Map<const Vec<3>>(x + 3 * a);
    total += m[a];
  }
  centre /= total;
  std::vector<std::pair<Real, Real>> rm(n);  // (distance, mass)
  for (std::size_t a = 0; a < n; ++a) rm[a] = {(Eigen::Map<const Vec<3>>(x + 3 * a) - centre).norm(), m[a]};
  std::sort(rm.begin(), rm.end());
  std::vector<Real> out;
  for (Real f : fractions) {
    const Real target = f * total - 1e-12 * total;
    Real enclosed = 0;
    std::size_t k = 0;
    while (k + 1 < n && enclosed + rm[k].second < target) enclosed += rm[k++].second;
    out.push_back(rm[k].first);
  }
  return out;
}

}  // namespace sphark
