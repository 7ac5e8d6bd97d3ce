#pragma once
// Test particle sets, generated identically on every rank (so each rank knows the global set
// and can check its own part against it): random or lattice positions in [0, 1)^D, global ids
// 0..N-1, a variable radius per particle.
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/neighbours/periodic_box.hpp"

namespace sphark::testing {

template <int D>
struct GlobalParticles {
  std::vector<Real> x;  // D per particle
  std::vector<Real> r;  // interaction radius
  std::size_t size() const { return r.size(); }
  Vec<D> position(std::size_t i) const { return Eigen::Map<const Vec<D>>(x.data() + D * i); }
};

// n random points (lattice: the nearest cube lattice, slightly perturbed), radii r0 (0.6 .. 1.4).
template <int D>
GlobalParticles<D> make_particles(std::size_t n, bool lattice, Real r0, std::uint64_t seed) {
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<Real> u(0, 1);
  GlobalParticles<D> p;
  if (lattice) {
    std::size_t side = 1;
    while (static_cast<std::size_t>(std::pow(side + 1, D)) <= n) ++side;
    n = static_cast<std::size_t>(std::pow(side, D));
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0, c = i; k < D; ++k, c /= side)
        p.x.push_back((Real(c % side) + 0.5 + 0.01 * (u(gen) - 0.5)) / Real(side));
  } else {
    for (std::size_t i = 0; i < D * n; ++i) p.x.push_back(u(gen));
  }
  for (std::size_t i = 0; i < n; ++i) p.r.push_back(r0 * (0.6 + 0.8 * u(gen)));
  return p;
}

template <int D>
std::optional<PeriodicBox<D>> unit_box(bool periodic) {
  if (!periodic) return std::nullopt;
  PeriodicBox<D> b;
  b.periodic.fill(true);
  return b;
}

// x_a - x_b, minimum image when periodic.
template <int D>
Vec<D> separation(const Vec<D>& a, const Vec<D>& b, const std::optional<PeriodicBox<D>>& box) {
  return box ? box->minimum_image(a - b) : Vec<D>(a - b);
}

}  // namespace sphark::testing
