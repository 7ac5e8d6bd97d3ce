// The largest smoothing length (SpmhdOptions::h_max, SWIFT's SPH:h_max): a particle whose root of
// seed 000 eqs. (4)-(5) lies beyond the cap takes h = h_max, the density sum (4) there and
// Omega = 1 (its h does not depend on rho: no grad-h terms), the others solve (5) as before.
//  - the capped particles' density is the direct sum (4) at h_max, the others satisfy (5);
//  - with about half of a disordered lattice capped, momentum and total energy are still
//    conserved to round-off (the scheme stays the gradient of one Lagrangian);
//  - with self-gravity the acceleration is still the gradient of the potential energy (the capped
//    particles' grad-h term, zeta, is zero);
//  - in a periodic box the default cap keeps the support within the minimum image: eight
//    particles in a unit box (their roots of (5) would reach across it) get h = 1 / (2 1.5 support)
//    and no neighbour, where the evaluation used to fail; an open box has no cap;
//  - a first guess 100x below the roots (as a restart's h of a particle that has since crossed
//    the box) reaches them: the lists grow 1.5x per attempt, 4x from the fifth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "spmhd_checks.hpp"
#include "sphark/neighbours/periodic_box.hpp"

namespace sphark {
namespace {

using K = CubicSpline<3>;

// Halfway between the two middle roots of (5): half of them lie beyond, none at it (a root at the
// cap would flip between capped and free under the finite differences).
Real between_middle_roots(std::vector<Real> h) {
  std::sort(h.begin(), h.end());
  return 0.5 * (h[h.size() / 2 - 1] + h[h.size() / 2]);
}

// The disordered periodic lattice of spmhd_checks.hpp with its RHS evaluated.
struct LatticeRhs {
  SpmhdScheme<3, K> s;
  std::vector<Real> y, ydot;
  explicit LatticeRhs(const SpmhdOptions& o)
      : s(test::lattice_masses<3>(test::LatticeCase{}), o, test::unit_box<3>()),
        y(test::lattice_state(s, test::LatticeCase{})), ydot(y.size()) {
    EXPECT_EQ(s.rhs(0, y.data(), ydot.data()), 0) << s.last_error();
  }
};

// Every conserving term on, h_max halfway between the lattice's two middle roots of (5).
SpmhdOptions half_capped_options() {
  SpmhdOptions o = test::conserving_options();
  o.h_max = between_middle_roots(LatticeRhs(o).s.h());
  return o;
}

TEST(SmoothingLengthCap, CappedParticlesTakeTheSumAtTheCapTheOthersEq5) {
  const SpmhdOptions o = half_capped_options();
  const LatticeRhs c(o);
  const SpmhdScheme<3, K>& s = c.s;
  const std::size_t n = s.particles(), capped = s.smoothing_lengths_at_cap();
  EXPECT_GT(capped, n / 4);
  EXPECT_LT(capped, 3 * n / 4);
  const auto x = vector_field<3>(c.y.data(), s.layout(), Field::Position);
  const MinimumImage<3> image(test::unit_box<3>());
  std::size_t counted = 0;
  for (std::size_t a = 0; a < n; ++a) {
    const Real h = s.h()[a], rho = s.rho()[a], m = s.masses()[a];
    if (h == o.h_max) {
      ++counted;
      Real sum = 0;  // seed 000, eq. (4), directly over every particle
      for (std::size_t b = 0; b < n; ++b)
        sum += s.masses()[b] * K::w(image(x.col(a).data(), x.col(b).data()).norm(), h);
      EXPECT_NEAR(rho, sum, 1e-13 * sum) << a;
      EXPECT_EQ(s.omega()[a], 1.0) << a;
      EXPECT_LT(rho, m * std::pow(o.eta / h, 3)) << a;  // its root of (5) lies beyond the cap
    } else {
      EXPECT_LT(h, o.h_max) << a;
      EXPECT_NEAR(h, o.eta * std::cbrt(m / rho), 1e-12 * h) << a;
    }
  }
  EXPECT_EQ(counted, capped);
}

TEST(SmoothingLengthCap, MomentumAndEnergyToRoundOffWithHalfTheParticlesCapped) {
  const LatticeRhs c(half_capped_options());
  ASSERT_GT(c.s.smoothing_lengths_at_cap(), c.s.particles() / 4);
  const auto [total, scale] = test::momentum_rate(c.s, c.ydot);
  ASSERT_GT(scale, 0);
  EXPECT_LT(total.norm(), 1e-14 * scale) << total.transpose();
  const test::EnergyRate e = test::energy_rate(c.s, c.y, c.ydot);
  ASSERT_GT(e.scale, 0);
  EXPECT_LT(std::abs(e.rate), 1e-14 * e.scale) << "dE/dt = " << e.rate << ", scale " << e.scale;
}

// A random clump of 120 equal-mass particles in the unit ball (open box), at rest, cold, no field.
std::vector<Real> clump_state(const SpmhdScheme<3, K>& s) {
  std::vector<Real> y(s.size(), 0);
  auto x = vector_field<3>(y.data(), s.layout(), Field::Position);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<Real> u(-1, 1);
  for (std::size_t a = 0; a < s.particles(); ++a) {
    Vec<3> p;
    do p = Vec<3>(u(rng), u(rng), u(rng));
    while (p.squaredNorm() > 1);
    x.col(a) = p;
  }
  return y;
}

TEST(SmoothingLengthCap, WithGravityTheAccelerationIsStillTheGradientOfThePotentialEnergy) {
  SpmhdOptions o;
  o.self_gravity = true;
  o.gravity_solver = GravitySolver::Direct;
  o.alpha_visc = o.alpha_u = 0;
  o.h_tolerance = 1e-14;  // the finite differences go through the h solve
  const std::vector<Real> masses(120, 1.0 / 120);
  std::vector<Real> h_free;
  {
    SpmhdScheme<3, K> s(masses, o);
    const std::vector<Real> y = clump_state(s);
    ASSERT_EQ(s.evaluate(0, y.data()), 0) << s.last_error();
    EXPECT_EQ(s.h_cap(), std::numeric_limits<Real>::infinity());  // an open box: no cap
    h_free = s.h();
  }
  o.h_max = between_middle_roots(h_free);
  SpmhdScheme<3, K> s(masses, o);
  const std::vector<Real> y = clump_state(s);
  std::vector<Real> ydot(y.size());
  ASSERT_EQ(s.rhs(0, y.data(), ydot.data()), 0) << s.last_error();
  ASSERT_GT(s.smoothing_lengths_at_cap(), 30u);
  const auto dv = vector_field<3>(ydot.data(), s.layout(), Field::Velocity);
  const std::size_t xo = s.layout().offset(Field::Position);
  const Real eps = 1e-6;
  Real worst = 0, scale = 0;
  std::size_t capped_checked = 0;
  for (std::size_t a = 0; a < s.particles(); a += 7) {
    capped_checked += s.h()[a] == o.h_max;
    for (int k = 0; k < 3; ++k) {
      std::vector<Real> yp = y, ym = y;
      yp[xo + 3 * a + k] += eps;
      ym[xo + 3 * a + k] -= eps;
      EXPECT_EQ(s.evaluate(0, yp.data()), 0);
      const Real e_plus = s.potential_energy();
      EXPECT_EQ(s.evaluate(0, ym.data()), 0);
      const Real force = -(e_plus - s.potential_energy()) / (2 * eps);
      const Real m_a = s.masses()[a] * dv(k, a);
      worst = std::max(worst, std::abs(force - m_a));
      scale = std::max(scale, std::abs(m_a));
    }
  }
  EXPECT_GT(capped_checked, 3u);
  ASSERT_GT(scale, 0);
  EXPECT_LT(worst, 1e-6 * scale);
}

TEST(SmoothingLengthCap, APeriodicBoxCapsTheSupportWithinItsMinimumImage) {
  test::LatticeCase c;
  c.nx = 2;  // eight particles: their roots of (5), h = 1.2 / 2, would reach across the box
  c.disorder = 0;
  SpmhdScheme<3, K> s(test::lattice_masses<3>(c), SpmhdOptions{}, test::unit_box<3>());
  const Real cap = 0.5 / (1.5 * K::support);
  EXPECT_DOUBLE_EQ(s.h_cap(), cap);
  const std::vector<Real> y = test::lattice_state(s, c);
  std::vector<Real> ydot(y.size());
  ASSERT_EQ(s.rhs(0, y.data(), ydot.data()), 0) << s.last_error();
  EXPECT_EQ(s.smoothing_lengths_at_cap(), 8u);
  for (std::size_t a = 0; a < 8; ++a) {
    EXPECT_EQ(s.h()[a], cap);
    EXPECT_NEAR(s.rho()[a], s.masses()[a] * K::w(0, cap), 1e-15 * s.rho()[a]);  // the self term alone
  }
}

TEST(SmoothingLengthCap, AGuessFarBelowTheRootsReachesThem) {
  SpmhdOptions o = test::conserving_options();
  const LatticeRhs from_box(o);  // the first guess from the bounding box: near the roots
  const std::vector<Real> roots = from_box.s.h();
  const Real least = *std::min_element(roots.begin(), roots.end());
  o.h_initial = least / 100;  // 1.5^8 = 26x would not reach: the 4x steps must
  const LatticeRhs from_far(o);
  ASSERT_EQ(from_far.s.h().size(), roots.size());
  for (std::size_t a = 0; a < roots.size(); ++a) EXPECT_NEAR(from_far.s.h()[a], roots[a], 1e-12 * roots[a]) << a;
  EXPECT_EQ(from_far.s.smoothing_lengths_at_cap(), 0u);
}

}  // namespace
}  // namespace sphark
