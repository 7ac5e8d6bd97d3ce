#include "sphark/scenes/gravitating_sphere/gravitating_sphere.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sphark {

Real default_u0(const std::string& profile) { return profile == "evrard" ? 0.05 : 1e-4; }

SpmhdOptions gravitating_sphere_options(const GravitatingSphereParams& p) {
  SpmhdOptions o;
  o.gamma = p.gamma;
  o.alpha_visc = p.alpha_visc;
  o.alpha_u = p.alpha_u;
  o.courant = p.courant;
  o.self_gravity = true;
  o.gravity_solver = p.gravity;
  o.gravity_theta = p.theta;
  o.force_courant = p.force_courant;
  return o;
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

}  // namespace sphark
