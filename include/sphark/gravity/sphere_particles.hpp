#pragma once
// Particle spheres with a known potential, for tests and benchmarks of self-gravity:
//   uniform     rho = 3 M / (4 pi R^3)           Phi = -G M (3 R^2 - r^2) / (2 R^3) inside
//   inverse_r   rho = M / (2 pi R^2 r)  (Evrard)  M(<r) = M (r/R)^2
// Equal masses m = M / n, h = eta (m / rho(r))^(1/3) from the exact density at each particle.
//   random_sphere:  radii from the inverse of M(<r) (uniform deviates), isotropic directions;
//                   std::mt19937_64 seeded, so the same seed gives the same set everywhere.
//   lattice_sphere: a simple cubic lattice centred on the origin (points at integer multiples
//                   of the spacing), cut at radius R; the spacing gives about n_target points.
//                   Its cubic symmetry makes the quadrupole moment vanish.
#include <cstdint>
#include <vector>

#include "sphark/gravity/self_gravity.hpp"

namespace sphark {

enum class SphereProfile { Uniform, InverseR };

struct SphereParticles {
  std::vector<Real> x, m, h;  // x: 3 x n
  std::size_t size() const { return m.size(); }
  GravitySources sources() const { return {x.data(), m.data(), h.data(), m.size()}; }
};

SphereParticles random_sphere(SphereProfile profile, std::size_t n, Real radius, Real mass, Real eta,
                              std::uint64_t seed);
SphereParticles lattice_sphere(std::size_t n_target, Real radius, Real mass, Real eta);

}  // namespace sphark
