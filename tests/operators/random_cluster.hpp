#pragma once
// A cluster of particles for the exact-property tests of the pair terms: random positions in a
// cube of side ~ one support radius (so most pairs interact), and random per-particle values of
// everything an operator reads (mass, h, rho, Omega, P, u, v, B, psi). The identities tested hold
// for ANY such values (they are algebraic, pair by pair), so nothing here is tuned.
#include <cmath>
#include <random>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/kernels/kernels.hpp"
#include "sphark/operators/pair_geometry.hpp"

namespace sphark::test {

using Vec3 = Eigen::Matrix<Real, 3, 1>;

template <int D>
struct Cluster {
  std::vector<Vec<D>> x, v;
  std::vector<Vec3> B;  // 3 components in 2D too
  std::vector<Real> m, h, rho, omega, P, u, psi;
  std::size_t size() const { return m.size(); }
  Real o(std::size_t a) const { return 1.0 / (omega[a] * rho[a] * rho[a]); }  // 1 / (Omega rho^2)
};

template <int D>
Cluster<D> random_cluster(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<Real> U(-1, 1);
  Cluster<D> c;
  for (std::size_t a = 0; a < n; ++a) {
    Vec<D> x, v;
    for (int k = 0; k < D; ++k) {
      x[k] = 0.9 * U(rng);  // cube of side 1.8; h in [0.8, 1.2] reaches 1.6 .. 2.4
      v[k] = U(rng);
    }
    c.x.push_back(x);
    c.v.push_back(v);
    c.B.push_back(Vec3(U(rng), U(rng), D == 2 ? 0.3 * U(rng) : U(rng)));
    c.m.push_back(1 + 0.5 * U(rng));
    c.h.push_back(1 + 0.2 * U(rng));
    c.rho.push_back(1 + 0.3 * U(rng));
    c.omega.push_back(1 + 0.1 * U(rng));
    c.P.push_back(1 + 0.5 * U(rng));
    c.u.push_back(1 + 0.5 * U(rng));
    c.psi.push_back(U(rng));
  }
  return c;
}

// The pair (a, b), a != b: x_ab = x_a - x_b, g_a = grad_a W_ab(h_a) = F_a x_ab,
// g_b = grad_a W_ab(h_b) = F_b x_ab; radial_a() and radial_b(): the same as RadialGradient.
template <int D>
struct Pair {
  Vec<D> x_ab;
  Real r, F_a, F_b;
  Vec<D> g_a, g_b;
  RadialGradient<D> radial_a() const { return {F_a, x_ab}; }
  RadialGradient<D> radial_b() const { return {F_b, x_ab}; }
};

template <class K, int D>
Pair<D> pair_of(const Cluster<D>& c, std::size_t a, std::size_t b) {
  Pair<D> p;
  p.x_ab = c.x[a] - c.x[b];
  p.r = p.x_ab.norm();
  p.F_a = K::f_over_r(p.r, c.h[a]);
  p.F_b = K::f_over_r(p.r, c.h[b]);
  p.g_a = p.F_a * p.x_ab;
  p.g_b = p.F_b * p.x_ab;
  return p;
}

// Accumulates sum and sum of magnitudes, for "zero to round-off" checks: |sum| < 1e-14 * scale.
struct RoundOffSum {
  Real sum = 0, scale = 0;
  void add(Real t) {
    sum += t;
    scale += std::abs(t);
  }
};

}  // namespace sphark::test
