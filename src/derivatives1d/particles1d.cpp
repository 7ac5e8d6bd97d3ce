#include "sphark/derivatives1d/particles1d.hpp"

#include <algorithm>
#include <random>
#include <stdexcept>

namespace sphark::d1 {

Particles1D uniform_particles(Index n, Real x_left, Real x_right) {
  if (n < 3) throw std::invalid_argument("uniform_particles: need N >= 3");
  Particles1D p;
  p.x_left = x_left;
  p.x_right = x_right;
  const Real dx = (x_right - x_left) / static_cast<Real>(n - 1);
  p.x.resize(n);
  for (Index i = 0; i < n; ++i) p.x[i] = x_left + static_cast<Real>(i) * dx;
  p.x[n - 1] = x_right;
  p.volume = Eigen::VectorXd::Constant(n, dx);  // seed 001 §V.I: dx inside, dx/2 on the boundary
  p.volume[0] = p.volume[n - 1] = 0.5 * dx;
  return p;
}

Eigen::VectorXd midpoint_volumes(const Eigen::VectorXd& x) {
  const Index n = x.size();
  Eigen::VectorXd v(n);
  for (Index i = 0; i < n; ++i) {
    const Real lo = i == 0 ? x[0] : 0.5 * (x[i - 1] + x[i]);
    const Real hi = i == n - 1 ? x[n - 1] : 0.5 * (x[i] + x[i + 1]);
    v[i] = hi - lo;
  }
  return v;
}

Particles1D random_particles(Index n, std::uint64_t seed, Real x_left, Real x_right) {
  if (n < 3) throw std::invalid_argument("random_particles: need N >= 3");
  Particles1D p;
  p.x_left = x_left;
  p.x_right = x_right;
  std::mt19937_64 rng(seed);
  std::vector<Real> xs{x_left, x_right};
  while (static_cast<Index>(xs.size()) < n) {
    const Real u = static_cast<Real>(rng() >> 11) * 0x1.0p-53;  // in [0, 1)
    const Real xi = x_left + (x_right - x_left) * u;
    if (xi > x_left && xi < x_right) xs.push_back(xi);  // u == 0 would duplicate x_l
  }
  std::sort(xs.begin(), xs.end());
  // two equal draws (probability ~N^2 2^-53) would give a zero volume and 0/0 in (5.16)
  if (std::adjacent_find(xs.begin(), xs.end()) != xs.end())
    throw std::runtime_error("random_particles: two particles coincide; choose another seed");
  p.x = Eigen::Map<Eigen::VectorXd>(xs.data(), n);
  p.volume = midpoint_volumes(p.x);
  return p;
}

}  // namespace sphark::d1
