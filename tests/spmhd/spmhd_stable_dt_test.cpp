// SpmhdScheme::max_stable_dt is a function of the state alone and fails with a quiet NaN:
//  - the value is the Courant limit min_a C h_a / (max(c_h,a, c_f,a) + (1 + beta)|v_a|) of the
//    per-particle quantities derived from y;
//  - it does not depend on what earlier calls (rhs at other states) left behind, beyond the
//    round-off of the h solve's Newton start; it is the same on a fresh scheme (a restart);
//  - a non-finite wave speed or field gives NaN with a reason, and the next good state a good value.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "spmhd_checks.hpp"

namespace sphark {
namespace {

using test::LatticeCase;

SpmhdOptions options() {
  SpmhdOptions o;
  o.cleaning = Cleaning::Constrained;
  o.alpha_b = 1;
  return o;
}

struct Case2D {
  LatticeCase lattice{16, 0.2, false, 5};
  SpmhdScheme<2> scheme{test::lattice_masses<2>(lattice), options(), test::unit_box<2>()};
  std::vector<Real> y = test::lattice_state(scheme, lattice);
};

// Another state of the same particles: other positions, velocities, energies and fields.
std::vector<Real> other_state(const Case2D& c) {
  LatticeCase other = c.lattice;
  other.seed = 99;
  other.disorder = 0.3;
  return test::lattice_state(c.scheme, other);
}

TEST(SpmhdStableDt, IsTheCourantLimitOfTheState) {
  Case2D c;
  const Real dt = c.scheme.max_stable_dt(0, c.y.data(), nullptr);
  ASSERT_EQ(c.scheme.evaluate(0, c.y.data()), 0);
  const SpmhdOptions& o = c.scheme.options();
  const auto v = vector_field<2>(c.y.data(), c.scheme.layout(), Field::Velocity);
  const auto& B = c.scheme.magnetic_field();
  Real expected = std::numeric_limits<Real>::infinity();
  for (std::size_t a = 0; a < c.scheme.particles(); ++a) {
    const Real rho = c.scheme.rho()[a], cs = std::sqrt(o.gamma * c.scheme.pressure()[a] / rho);
    const Real b2 = B[3 * a] * B[3 * a] + B[3 * a + 1] * B[3 * a + 1] + B[3 * a + 2] * B[3 * a + 2];
    const Real fast = std::sqrt(cs * cs + b2 / rho);
    const Real vsig = std::max(c.scheme.cleaning_speeds()[a], fast) + (1 + o.beta_visc) * v.col(a).norm();
    expected = std::min(expected, o.courant * c.scheme.h()[a] / vsig);
  }
  EXPECT_DOUBLE_EQ(dt, expected);
  EXPECT_GT(dt, 0);
}

TEST(SpmhdStableDt, DependsOnTheStateAloneNotOnEarlierCalls) {
  Case2D fresh, used;
  const Real dt_fresh = fresh.scheme.max_stable_dt(0, fresh.y.data(), nullptr);
  // the same state after right-hand sides at other states (other h, lists, wave speeds)
  const std::vector<Real> y_other = other_state(used);
  std::vector<Real> ydot(y_other.size());
  ASSERT_EQ(used.scheme.rhs(0, y_other.data(), ydot.data()), 0) << used.scheme.last_error();
  const Real dt_other = used.scheme.max_stable_dt(0, y_other.data(), nullptr);
  ASSERT_EQ(used.scheme.rhs(0, y_other.data(), ydot.data()), 0);
  const Real dt_used = used.scheme.max_stable_dt(0, used.y.data(), nullptr);
  std::cout << "fresh " << dt_fresh << ", after other states " << dt_used << " (other state " << dt_other
            << "), relative difference " << std::abs(dt_used - dt_fresh) / dt_fresh << "\n";
  EXPECT_GT(std::abs(dt_other - dt_fresh), 1e-3 * dt_fresh);  // the other state has another limit
  EXPECT_NEAR(dt_used, dt_fresh, 1e-14 * dt_fresh);  // the h solve's Newton start: round-off only
  // twice at the same state, and after rhs at that state: the same bits
  EXPECT_EQ(used.scheme.max_stable_dt(0, used.y.data(), nullptr), dt_used);
  ASSERT_EQ(used.scheme.rhs(0, used.y.data(), ydot.data()), 0);
  EXPECT_EQ(used.scheme.max_stable_dt(0, used.y.data(), nullptr), dt_used);
}

TEST(SpmhdStableDt, FailureIsAQuietNaNWithAReason) {
  Case2D c;
  const Real good = c.scheme.max_stable_dt(0, c.y.data(), nullptr);
  std::vector<Real> y = c.y;
  scalar_field(y.data(), c.scheme.layout(), Field::InternalEnergy)(7) = std::numeric_limits<Real>::infinity();
  EXPECT_TRUE(std::isnan(c.scheme.max_stable_dt(0, y.data(), nullptr)));
  EXPECT_NE(c.scheme.last_error().find("wave speed"), std::string::npos) << c.scheme.last_error();
  y = c.y;
  vector_field<3>(y.data(), c.scheme.layout(), Field::MagneticField)(0, 3) = std::numeric_limits<Real>::quiet_NaN();
  EXPECT_TRUE(std::isnan(c.scheme.max_stable_dt(0, y.data(), nullptr)));
  EXPECT_NE(c.scheme.last_error().find("particle 3"), std::string::npos) << c.scheme.last_error();
  EXPECT_EQ(c.scheme.max_stable_dt(0, c.y.data(), nullptr), good);  // the good state again
}

}  // namespace
}  // namespace sphark
