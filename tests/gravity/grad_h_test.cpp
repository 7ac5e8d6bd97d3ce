// The gravitational grad-h term (gravity_grad_h.hpp) makes the force the exact gradient of the
// energy when h adapts (Price & Monaghan 2007, §3): with h_a = eta (m_a / rho_a)^(1/3) solved to
// round-off from the density summation, E_g(x) = (1/2) sum_a m_a Phi_a (direct summation, self
// terms included), and
//   F_a = m_a (a_softened + a_grad-h),
// F_a must equal -dE_g/dx_a by central finite differences (h re-solved at every displaced
// configuration) to the difference error (~1e-9 here: asserted 1e-6), and without the grad-h
// term it must not (the term is > 1e-3 of the force on this clump). Also: the grad-h pair
// forces are antisymmetric (momentum conserved to round-off).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <random>
#include <vector>

#include "gravity_test_support.hpp"
#include "sphark/gravity/direct_gravity.hpp"
#include "sphark/gravity/gravity_grad_h.hpp"
#include "sphark/operators/density_summation.hpp"

using namespace sphark;

namespace {

template <class K>
class GradHGravityTest : public ::testing::Test {};
TYPED_TEST_SUITE(GradHGravityTest, gravity_test::AllKernels);

constexpr Real kEta = 1.2;

struct Clump {
  std::vector<Real> x, m;
  std::size_t size() const { return m.size(); }
};

Clump random_clump() {
  std::mt19937_64 g(31);
  std::normal_distribution<Real> pos(0, 0.3);
  std::uniform_real_distribution<Real> w(0.7, 1.3);
  Clump c;
  for (int i = 0; i < 40; ++i) {
    c.x.insert(c.x.end(), {pos(g), pos(g), 0.6 * pos(g)});
    c.m.push_back(w(g) / 40);
  }
  return c;
}

Real distance(const Clump& c, std::size_t a, std::size_t b) {
  return std::hypot(c.x[3 * a] - c.x[3 * b], c.x[3 * a + 1] - c.x[3 * b + 1], c.x[3 * a + 2] - c.x[3 * b + 2]);
}

// h, rho, Omega of every particle: Newton on rho(h) = m (eta/h)^3 (seed 000, eqs. (4)-(5)) to
// round-off, from the guesses in h, each step limited to 20 % of h.
template <class K>
void solve_density(const Clump& c, std::vector<Real>& h, std::vector<Real>& rho, std::vector<Real>& omega) {
  const std::size_t n = c.size();
  rho.resize(n), omega.resize(n);
  for (std::size_t a = 0; a < n; ++a) {
    Real sum = 0, dsum = 0;
    int converged = 0;
    for (int it = 0; it < 100; ++it) {
      sum = dsum = 0;
      for (std::size_t b = 0; b < n; ++b) {
        sum += c.m[b] * K::w(distance(c, a, b), h[a]);
        dsum += c.m[b] * kernel_dw_dh<3, K>(distance(c, a, b), h[a]);
      }
      const Real target = c.m[a] * std::pow(kEta / h[a], 3);
      const Real step = std::clamp((sum - target) / (dsum + 3 * target / h[a]), -0.2 * h[a], 0.2 * h[a]);
      h[a] -= step;
      if (std::abs(step) < 1e-14 * h[a]) converged += 1;  // then one more step, to round-off
      if (converged == 2) break;
    }
    rho[a] = sum;
    omega[a] = 1 + h[a] / (3 * rho[a]) * dsum;
  }
}

template <class K>
Real energy(const Clump& c, std::vector<Real> h) {
  std::vector<Real> rho, omega, acc(3 * c.size()), pot(c.size());
  solve_density<K>(c, h, rho, omega);
  DirectGravity<K> direct(GravityOptions{});
  return direct.compute({c.x.data(), c.m.data(), h.data(), c.size()}, acc.data(), pot.data());
}

}  // namespace

TYPED_TEST(GradHGravityTest, ForceIsMinusTheEnergyGradient) {
  using K = TypeParam;
  const Clump c = random_clump();
  const std::size_t n = c.size();
  std::vector<Real> h(n, 0.3), rho, omega;
  solve_density<K>(c, h, rho, omega);
  // the softened force (direct) and zeta
  std::vector<Real> acc(3 * n), pot(n), zeta_omega(n);
  DirectGravity<K>(GravityOptions{}).compute({c.x.data(), c.m.data(), h.data(), n}, acc.data(), pot.data());
  for (std::size_t a = 0; a < n; ++a) {
    Real s = zeta_init<K>(c.m[a], h[a]);
    for (std::size_t b = 0; b < n; ++b)
      if (b != a) s += zeta_pair<K>(c.m[b], distance(c, a, b), h[a]);
    zeta_omega[a] = zeta_finish(s, h[a], rho[a]) / omega[a];
  }
  std::vector<Real> grad_h(3 * n, 0);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) {
      if (b == a) continue;
      const Vec<3> xab(c.x[3 * a] - c.x[3 * b], c.x[3 * a + 1] - c.x[3 * b + 1], c.x[3 * a + 2] - c.x[3 * b + 2]);
      const Vec<3> g = grad_h_gravity_pair<K>(1.0, c.m[b], xab, xab.norm(), h[a], h[b], zeta_omega[a], zeta_omega[b]);
      for (int k = 0; k < 3; ++k) grad_h[3 * a + k] += g[k];
    }
  EXPECT_LT(gravity_test::momentum_error(c.m, grad_h), 1e-14);
  // -dE/dx by central differences
  Real err_with = 0, err_without = 0, scale = 0;
  const Real d = 1e-6;
  for (std::size_t a = 0; a < n; ++a)
    for (int k = 0; k < 3; ++k) {
      Clump plus = c, minus = c;
      plus.x[3 * a + k] += d, minus.x[3 * a + k] -= d;
      const Real fd = -(energy<K>(plus, h) - energy<K>(minus, h)) / (2 * d);
      const Real with = c.m[a] * (acc[3 * a + k] + grad_h[3 * a + k]), without = c.m[a] * acc[3 * a + k];
      err_with = std::max(err_with, std::abs(with - fd));
      err_without = std::max(err_without, std::abs(without - fd));
      scale = std::max(scale, std::abs(fd));
    }
  std::printf("%s: max |F - (-dE/dx)| / max |F|: with grad-h %.2e, without %.2e\n", std::string(K::name).c_str(),
              err_with / scale, err_without / scale);
  EXPECT_LT(err_with, 1e-6 * scale);
  EXPECT_GT(err_without, 1e-3 * scale);
}

