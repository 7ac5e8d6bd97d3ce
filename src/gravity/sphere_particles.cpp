// Particle spheres (see sphark/gravity/sphere_particles.hpp).
#include "sphark/gravity/sphere_particles.hpp"

#include <cmath>
#include <random>

namespace sphark {

namespace {
Real uniform01(std::mt19937_64& g) { return (static_cast<Real>(g() >> 11) + 0.5) * 0x1.0p-53; }
}  // namespace

SphereParticles random_sphere(SphereProfile profile, std::size_t n, Real radius, Real mass, Real eta,
                              std::uint64_t seed) {
  std::mt19937_64 g(seed);
  SphereParticles p;
  p.x.resize(3 * n);
  p.m.assign(n, mass / static_cast<Real>(n));
  p.h.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Real u = uniform01(g);
    const Real r = profile == SphereProfile::Uniform ? radius * std::cbrt(u) : radius * std::sqrt(u);
    const Real cz = 2 * uniform01(g) - 1, az = 2 * kPi * uniform01(g), sz = std::sqrt(1 - cz * cz);
    p.x[3 * i] = r * sz * std::cos(az);
    p.x[3 * i + 1] = r * sz * std::sin(az);
    p.x[3 * i + 2] = r * cz;
    const Real rho = profile == SphereProfile::Uniform ? 3 * mass / (4 * kPi * radius * radius * radius)
                                                       : mass / (2 * kPi * radius * radius * r);
    p.h[i] = eta * std::cbrt(p.m[i] / rho);
  }
  return p;
}

SphereParticles lattice_sphere(std::size_t n_target, Real radius, Real mass, Real eta) {
  const Real dx = radius * std::cbrt(4 * kPi / (3 * static_cast<Real>(n_target)));
  const int k_max = static_cast<int>(radius / dx) + 1;
  SphereParticles p;
  for (int i = -k_max; i <= k_max; ++i)
    for (int j = -k_max; j <= k_max; ++j)
      for (int k = -k_max; k <= k_max; ++k) {
        const Real x = i * dx, y = j * dx, z = k * dx;
        if (x * x + y * y + z * z > radius * radius) continue;
        p.x.insert(p.x.end(), {x, y, z});
      }
  const std::size_t n = p.x.size() / 3;
  p.m.assign(n, mass / static_cast<Real>(n));
  p.h.assign(n, eta * dx);
  return p;
}

}  // namespace sphark
