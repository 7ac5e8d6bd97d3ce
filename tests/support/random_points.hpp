#pragma once
// n uniform random points in the unit cube, D coordinates each (a fixed seed: reproducible).
#include <cstddef>
#include <random>
#include <vector>

#include "sphark/core/types.hpp"

namespace sphark::test {

template <int D>
std::vector<Real> random_points(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<Real> u(0.0, 1.0);
  std::vector<Real> x(D * n);
  for (auto& v : x) v = u(rng);
  return x;
}

}  // namespace sphark::test
