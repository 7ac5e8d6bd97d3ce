#include "sphark/initial/spheres.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <stdexcept>

namespace sphark {

namespace {

void check(const SphereSpec& s) {
  if (s.particles == 0 || !(s.radius > 0) || !(s.mass > 0))
    throw std::invalid_argument("sphere initial conditions: need particles >= 1, radius > 0 and mass > 0");
}

Real ball_volume(Real r) { return 4.0 / 3.0 * kPi * r * r * r; }

// uniform in [0, 1): the top 53 bits of a 64-bit draw (the same on every standard library)
Real unit_draw(std::mt19937_64& rng) { return static_cast<Real>(rng() >> 11) * 0x1.0p-53; }

ParticlePlacement random_ball(const SphereSpec& s) {
  std::mt19937_64 rng(s.seed);
  ParticlePlacement p;
  p.x.reserve(3 * s.particles);
  while (p.size() < s.particles) {  // rejection from the enclosing cube
    const Real x = s.radius * (2 * unit_draw(rng) - 1), y = s.radius * (2 * unit_draw(rng) - 1),
               z = s.radius * (2 * unit_draw(rng) - 1);
    if (x * x + y * y + z * z < s.radius * s.radius) p.x.insert(p.x.end(), {x, y, z});
  }
  p.spacing = std::cbrt(ball_volume(s.radius) / static_cast<Real>(s.particles));
  return p;
}

// The spacing whose ball count is nearest the request. The ball of radius R about the origin
// holds the sites of the unit lattice with |u| < R / d: the achievable counts are the
// cumulative counts of its shells (sites at one |u|, equal up to round-off). Pick the shell
// whose cumulative count is nearest, and put R / d midway between it and the next shell, so
// that no shell lies within round-off of the surface (where it would be kept in part).
Real spacing_for_count(CloseLattice lattice, Real radius, std::size_t wanted) {
  const Real scale = radius / close_packed_spacing(static_cast<Real>(wanted) / ball_volume(radius));  // ~ R / d
  const std::vector<Real> u = close_packed_ball(lattice, 1.0, 1.25 * scale + 3);
  std::vector<Real> r(u.size() / 3);
  for (std::size_t a = 0; a < r.size(); ++a)
    r[a] = std::sqrt(u[3 * a] * u[3 * a] + u[3 * a + 1] * u[3 * a + 1] + u[3 * a + 2] * u[3 * a + 2]);
  std::sort(r.begin(), r.end());
  std::size_t best_end = 0;  // sites [0, best_end) are the chosen ball
  long long best_miss = static_cast<long long>(wanted);
  for (std::size_t a = 1; a < r.size(); ++a) {
    if (r[a] - r[a - 1] <= 1e-9 * r[a]) continue;  // same shell
    const long long miss = std::llabs(static_cast<long long>(a) - static_cast<long long>(wanted));
    if (miss < best_miss) best_miss = miss, best_end = a;
    if (a > 2 * wanted) break;
  }
  if (best_end == 0) throw std::logic_error("spacing_for_count: no shell found");
  return radius / (0.5 * (r[best_end - 1] + r[best_end]));
}

}  // namespace

ParticlePlacement uniform_sphere(const SphereSpec& spec) {
  check(spec);
  ParticlePlacement p;
  if (spec.random) {
    p = random_ball(spec);
  } else {
    p.spacing = spacing_for_count(spec.lattice, spec.radius, spec.particles);
    p.x = close_packed_ball(spec.lattice, p.spacing, spec.radius);
  }
  p.particle_mass = spec.mass / static_cast<Real>(p.size());
  return p;
}

void stretch_to_inverse_r(std::vector<Real>& x, Real radius) {
  for (std::size_t a = 0; a + 2 < x.size(); a += 3) {
    const Real r = std::sqrt(x[a] * x[a] + x[a + 1] * x[a + 1] + x[a + 2] * x[a + 2]);
    const Real f = std::sqrt(r / radius);  // |x| -> R (r/R)^(3/2) = r (r/R)^(1/2)
    for (int k = 0; k < 3; ++k) x[a + k] *= f;
  }
}

ParticlePlacement evrard_sphere(const SphereSpec& spec) {
  ParticlePlacement p = uniform_sphere(spec);
  stretch_to_inverse_r(p.x, spec.radius);
  return p;
}

SphereInBox sphere_in_box(const SphereSpec& spec, Real side_over_radius, Real density_contrast, BoxFit fit) {
  check(spec);
  if (spec.random) throw std::invalid_argument("sphere_in_box: random placement is not supported");
  if (!(side_over_radius > 2) || !(density_contrast >= 1))
    throw std::invalid_argument("sphere_in_box: need side > 2 R and contrast >= 1");
  SphereInBox out;
  const Real side0 = side_over_radius * spec.radius;
  const Real stretch = std::cbrt(density_contrast);  // ambient spacing / sphere spacing
  const Real d_sphere = fit == BoxFit::nearest_count
                            ? spacing_for_count(spec.lattice, spec.radius, spec.particles)
                            : close_packed_spacing(static_cast<Real>(spec.particles) / ball_volume(spec.radius));
  const Real cell = std::sqrt(2.0) * d_sphere * stretch;  // fcc cubic cell of the ambient
  out.ambient_cells = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(side0 / cell)));
  if (fit == BoxFit::nearest_count) {
    out.side = cell * static_cast<Real>(out.ambient_cells);
    out.sphere.spacing = d_sphere;
  } else {
    out.side = side0;
    out.sphere.spacing = out.side / static_cast<Real>(out.ambient_cells) / std::sqrt(2.0) / stretch;
  }
  if (!(out.side > 2 * spec.radius)) throw std::invalid_argument("sphere_in_box: the box does not hold the sphere");
  out.ambient_spacing = out.sphere.spacing * stretch;
  out.sphere.x = close_packed_ball(spec.lattice, out.sphere.spacing, spec.radius);
  if (out.sphere.size() == 0) throw std::invalid_argument("sphere_in_box: too few particles for one lattice cell");
  out.sphere.particle_mass = spec.mass / static_cast<Real>(out.sphere.size());
  out.ambient = fcc_periodic_cube(out.side, out.ambient_cells, spec.radius);
  out.sphere_lattice_density = out.sphere.particle_mass * close_packed_number_density(out.sphere.spacing);
  out.ambient_lattice_density = out.sphere.particle_mass * close_packed_number_density(out.ambient_spacing);
  return out;
}

}  // namespace sphark
