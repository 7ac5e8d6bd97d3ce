// The quadrupole-order cell-cell expansion (multipole.hpp): its error falls as (size/distance)^3
// (the order of the truncation), re-expansion about another centre is exact, and -- the
// momentum argument of docs/gravity.md -- the total force of B on A is minus that of A on B to
// round-off, although each is only accurate to the truncation error.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "sphark/gravity/multipole.hpp"

using namespace sphark;

namespace {

// A cluster of random masses in a ball of radius `size` about `centre`; moments about its COM.
struct Cluster {
  std::vector<Real> x, m;
  Real com[3] = {0, 0, 0}, mass = 0, quad[6] = {0, 0, 0, 0, 0, 0};

  Cluster(const Real centre[3], Real size, unsigned seed) {
    std::mt19937_64 g(seed);
    std::uniform_real_distribution<Real> u(-1, 1), w(0.5, 1.5);
    while (m.size() < 20) {
      const Real p[3] = {u(g), u(g), u(g)};
      if (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] > 1) continue;
      for (int c = 0; c < 3; ++c) x.push_back(centre[c] + size * p[c]);
      m.push_back(w(g));
    }
    for (std::size_t i = 0; i < m.size(); ++i) {
      mass += m[i];
      for (int c = 0; c < 3; ++c) com[c] += m[i] * x[3 * i + c];
    }
    for (Real& c : com) c /= mass;
    for (std::size_t i = 0; i < m.size(); ++i) {
      const Real s[3] = {x[3 * i] - com[0], x[3 * i + 1] - com[1], x[3 * i + 2] - com[2]};
      const Real q[6] = {s[0] * s[0], s[0] * s[1], s[0] * s[2], s[1] * s[1], s[1] * s[2], s[2] * s[2]};
      for (int c = 0; c < 6; ++c) quad[c] += m[i] * q[c];
    }
  }
  std::size_t size() const { return m.size(); }
};

// The expansion of `source` about target's COM.
LocalExpansion expansion(const Cluster& target, const Cluster& source) {
  LocalExpansion L;
  const Real R[3] = {target.com[0] - source.com[0], target.com[1] - source.com[1], target.com[2] - source.com[2]};
  add_far_field(L, R, source.mass, source.quad);
  return L;
}

// Largest relative error of grad psi and psi (the expansion against the exact sum) over target.
void errors(const Cluster& target, const Cluster& source, Real& force_error, Real& potential_error) {
  const LocalExpansion L = expansion(target, source);
  force_error = potential_error = 0;
  for (std::size_t a = 0; a < target.size(); ++a) {
    Real psi = 0, grad[3] = {0, 0, 0};
    for (std::size_t b = 0; b < source.size(); ++b) {
      Real d[3], r2 = 0;
      for (int c = 0; c < 3; ++c) d[c] = target.x[3 * a + c] - source.x[3 * b + c], r2 += d[c] * d[c];
      const Real ir = 1 / std::sqrt(r2);
      psi += source.m[b] * ir;
      for (int c = 0; c < 3; ++c) grad[c] -= source.m[b] * ir * ir * ir * d[c];
    }
    const Real s[3] = {target.x[3 * a] - target.com[0], target.x[3 * a + 1] - target.com[1],
                       target.x[3 * a + 2] - target.com[2]};
    Real value, g[3];
    value_and_gradient_at(L, s, value, g);
    const Real gn = std::hypot(grad[0], grad[1], grad[2]);
    force_error = std::max(force_error, std::hypot(g[0] - grad[0], g[1] - grad[1], g[2] - grad[2]) / gn);
    potential_error = std::max(potential_error, std::abs(value - psi) / psi);
  }
}

const Real kA[3] = {0.3, -0.2, 0.1}, kB[3] = {1.0, 0.5, -0.4};  // |kA - kB| ~ 1

}  // namespace

TEST(Multipole, ErrorIsThirdOrderInSizeOverDistance) {
  Real f_prev = 0, p_prev = 0;
  for (Real size : {0.08, 0.04, 0.02}) {
    Real f, p;
    errors(Cluster(kA, size, 1), Cluster(kB, size, 2), f, p);
    if (f_prev > 0) {
      // halving the size: the force error 2^3 = 8 times smaller (the truncated terms are of
      // total order 3); the potential's at least 8 times (its order-3 term is B's octupole
      // alone, order-4 terms are of similar size here: measured 12-14)
      EXPECT_GT(f_prev / f, 7.0) << size;
      EXPECT_LT(f_prev / f, 9.0) << size;
      EXPECT_GT(p_prev / p, 7.0) << size;
    }
    f_prev = f, p_prev = p;
  }
  EXPECT_LT(f_prev, 1e-4);
}

TEST(Multipole, ReExpansionIsExact) {
  const Cluster target(kA, 0.1, 3), source(kB, 0.1, 4);
  const LocalExpansion L = expansion(target, source);
  const Real d[3] = {0.03, -0.05, 0.02}, s[3] = {0.01, 0.02, -0.04};
  LocalExpansion child;
  add_shifted(child, L, d);
  Real v1, g1[3], v2, g2[3];
  value_and_gradient_at(child, s, v1, g1);
  const Real ds[3] = {d[0] + s[0], d[1] + s[1], d[2] + s[2]};
  value_and_gradient_at(L, ds, v2, g2);
  EXPECT_NEAR(v1, v2, 1e-14 * std::abs(v2));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(g1[c], g2[c], 1e-13 * std::hypot(g2[0], g2[1], g2[2]));
}

// Sum over A of m_a grad psi_B(x_a) + sum over B of m_b grad psi_A(x_b) = 0 to round-off, for
// clusters so large (size/distance = 0.25) that each total is off by ~1e-3.
TEST(Multipole, TotalForcesAreEqualAndOpposite) {
  const Cluster A(kA, 0.3, 5), B(kB, 0.3, 6);
  Real fa[3] = {0, 0, 0}, fb[3] = {0, 0, 0}, exact[3] = {0, 0, 0};
  const LocalExpansion LA = expansion(A, B), LB = expansion(B, A);
  for (const auto& [target, L, f] : {std::tuple{&A, &LA, fa}, std::tuple{&B, &LB, fb}})
    for (std::size_t a = 0; a < target->size(); ++a) {
      const Real s[3] = {target->x[3 * a] - target->com[0], target->x[3 * a + 1] - target->com[1],
                         target->x[3 * a + 2] - target->com[2]};
      Real v, g[3];
      value_and_gradient_at(*L, s, v, g);
      for (int c = 0; c < 3; ++c) f[c] += target->m[a] * g[c];
    }
  for (std::size_t a = 0; a < A.size(); ++a)
    for (std::size_t b = 0; b < B.size(); ++b) {
      Real d[3], r2 = 0;
      for (int c = 0; c < 3; ++c) d[c] = A.x[3 * a + c] - B.x[3 * b + c], r2 += d[c] * d[c];
      for (int c = 0; c < 3; ++c) exact[c] -= A.m[a] * B.m[b] * d[c] / (r2 * std::sqrt(r2));
    }
  const Real scale = std::hypot(fa[0], fa[1], fa[2]);
  EXPECT_LT(std::hypot(fa[0] + fb[0], fa[1] + fb[1], fa[2] + fb[2]) / scale, 1e-14);
  EXPECT_GT(std::hypot(fa[0] - exact[0], fa[1] - exact[1], fa[2] - exact[2]) / scale, 1e-5);  // not exact
}
