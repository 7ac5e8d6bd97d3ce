#pragma once
// 1D particle sets of seed 001 §V: positions x_i, volumes |Omega_i|, one particle on each
// end of the domain [x_l, x_r]. Positions are stored sorted (x_0 = x_l, x_{N-1} = x_r).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "sphark/core/types.hpp"

namespace sphark::d1 {

struct Particles1D {
  Eigen::VectorXd x;       // positions, sorted ascending
  Eigen::VectorXd volume;  // |Omega_i|
  Real x_left = 0, x_right = 1;
  Index size() const { return x.size(); }
  Index left() const { return 0; }               // the particle on x_l
  Index right() const { return x.size() - 1; }   // the particle on x_r
  bool on_boundary(Index i) const { return i == left() || i == right(); }
  Real max_volume() const { return volume.maxCoeff(); }
};

// seed 001 §V.I, Figure 1: x_1 = x_l, x_N = x_r, equidistant; the two boundary particles have
// half the volume dx/2 of the others (dx = (x_r - x_l) / (N - 1)). Requires N >= 3.
Particles1D uniform_particles(Index n, Real x_left = 0, Real x_right = 1);

// seed 001 §V.II, Figure 3: one particle fixed on each boundary, N - 2 particles uniformly at
// random in (x_l, x_r); sub-domain boundaries half way between neighbours (midpoint volumes).
// Nested: the interior particles of the set with N particles are the first N - 2 draws of the
// stream seeded by `seed`, so the first N particles keep their positions as N grows.
// The draw u = (mt19937_64() >> 11) * 2^-53 is implementation-independent. Requires N >= 3.
Particles1D random_particles(Index n, std::uint64_t seed, Real x_left = 0, Real x_right = 1);

// Midpoint volumes of sorted positions: |Omega_i| = (x_{i+1} - x_{i-1}) / 2, half cells at the ends.
Eigen::VectorXd midpoint_volumes(const Eigen::VectorXd& sorted_x);

// Smoothing length h = c * max_i |Omega_i|   (seed 001, eq. (5.19); for uniform particles this is
// h = c * dx as in §V.I).
inline Real smoothing_length(const Particles1D& p, Real c) { return c * p.max_volume(); }

}  // namespace sphark::d1
