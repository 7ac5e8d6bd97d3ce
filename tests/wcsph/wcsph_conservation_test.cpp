// Exact properties of the WCSPH + velocity-cleaning right-hand side:
//  - total momentum is conserved to round-off (no external force), with viscosity, density
//    diffusion and cleaning all on;
//  - the velocity-cleaning subsystem conserves its energy (seed 000, eq. (37)) to round-off
//    for sigma = 0, and only loses energy with damping.
#include <gtest/gtest.h>


#include "sphark/kernels/kernels.hpp"
#include "sphark/schemes/wcsph/wcsph_system.hpp"
#include "../support/wcsph_lattice.hpp"

using namespace sphark;

namespace {
using Sys = WcsphSystem<2, WendlandC2<2>>;

// A disturbed square lattice with random velocities, densities and psi (tests/support).
std::vector<Real> disturbed_state(const Sys& sys, unsigned seed, Real dx) {
  const int side = static_cast<int>(std::lround(std::sqrt(static_cast<double>(sys.layout().particles()))));
  return test::WcsphLattice{side, dx, 1000, 20, seed, 1e4}.disturbed_state(sys.layout());
}

WcsphParams<2> params(bool cleaning, Real sigma, bool subsystem) {
  WcsphParams<2> p;
  const Real dx = 0.04;
  p.mass = 1000 * dx * dx;
  p.h = 1.3 * dx;
  p.alpha = 0.1;
  p.delta = 0.1;
  p.cleaning = cleaning;
  p.clean_sigma = sigma;
  p.cleaning_subsystem_only = subsystem;
  return p;
}
}  // namespace

TEST(WcsphRhs, ConservesMomentumToRoundOff) {
  for (bool cleaning : {false, true}) {
    Sys sys(400, params(cleaning, 0.5, false));
    auto y = disturbed_state(sys, 11, 0.04);
    std::vector<Real> ydot(y.size());
    ASSERT_EQ(sys.rhs(0, y.data(), ydot.data()), 0) << sys.last_error();
    const auto dv = vector_field<2>(ydot.data(), sys.layout(), Field::Velocity);
    Vec<2> total = Vec<2>::Zero();
    Real scale = 0;
    for (Index a = 0; a < dv.cols(); ++a) {
      total += sys.params().mass * dv.col(a);
      scale += sys.params().mass * dv.col(a).norm();
    }
    ASSERT_GT(scale, 0);
    EXPECT_LT(total.norm(), 1e-13 * scale) << "cleaning=" << cleaning;
  }
}

namespace {
// dE/dt of eq. (37), E = sum m (v^2/2 + psi^2 / (2 c_h^2 rho^2)), with rho frozen.
Real cleaning_energy_rate(Sys& sys, const std::vector<Real>& y) {
  std::vector<Real> ydot(y.size());
  EXPECT_EQ(sys.rhs(0, y.data(), ydot.data()), 0) << sys.last_error();
  const StateLayout& L = sys.layout();
  const auto v = vector_field<2>(y.data(), L, Field::Velocity);
  const auto dv = vector_field<2>(ydot.data(), L, Field::Velocity);
  const auto rho = scalar_field(y.data(), L, Field::Density);
  const auto psi = scalar_field(y.data(), L, Field::Psi);
  const auto dpsi = scalar_field(ydot.data(), L, Field::Psi);
  const Real m = sys.params().mass, ch = sys.params().cleaning_speed();
  Real rate = 0;
  for (Index a = 0; a < v.cols(); ++a)
    rate += m * v.col(a).dot(dv.col(a)) + m * psi[a] * dpsi[a] / (ch * ch * rho[a] * rho[a]);
  return rate;
}

// Scale of the individual terms, to judge "round-off".
Real cleaning_power_scale(Sys& sys, const std::vector<Real>& y) {
  std::vector<Real> ydot(y.size());
  sys.rhs(0, y.data(), ydot.data());
  const StateLayout& L = sys.layout();
  const auto v = vector_field<2>(y.data(), L, Field::Velocity);
  const auto dv = vector_field<2>(ydot.data(), L, Field::Velocity);
  Real s = 0;
  for (Index a = 0; a < v.cols(); ++a) s += sys.params().mass * std::abs(v.col(a).dot(dv.col(a)));
  return s;
}
}  // namespace

TEST(VelocityCleaning, SubsystemConservesEnergyWithoutDamping) {
  Sys sys(400, params(true, 0.0, true));
  const auto y = disturbed_state(sys, 5, 0.04);
  const Real scale = cleaning_power_scale(sys, y);
  ASSERT_GT(scale, 0);
  EXPECT_LT(std::abs(cleaning_energy_rate(sys, y)), 1e-12 * scale);
}

TEST(VelocityCleaning, SubsystemOnlyLosesEnergyWithDamping) {
  Sys undamped(400, params(true, 0.0, true));
  Sys damped(400, params(true, 0.8, true));
  for (unsigned seed : {1u, 2u, 3u}) {
    const auto y = disturbed_state(damped, seed, 0.04);
    const Real rate = cleaning_energy_rate(damped, y);
    EXPECT_LT(rate, 0);
    // the loss is exactly the damping term of eq. (24): -sum m psi^2 / (c_h^2 rho^2 tau)
    const StateLayout& L = damped.layout();
    const auto rho = scalar_field(y.data(), L, Field::Density);
    const auto psi = scalar_field(y.data(), L, Field::Psi);
    const Real ch = damped.params().cleaning_speed();
    Real expect = 0;
    for (Index a = 0; a < psi.size(); ++a)
      expect -= damped.params().mass * psi[a] * psi[a] * damped.params().cleaning_rate() / (ch * ch * rho[a] * rho[a]);
    EXPECT_NEAR(rate, expect, 1e-11 * std::abs(expect)) << "seed " << seed;
    (void)undamped;
  }
}

TEST(VelocityCleaning, ConjugateOperatorsAreAdjoint) {
  // sum_a m_a/rho_a psi_a div v_a = sum_a m_a v_a . (grad psi_a / rho_a)  (discrete integration
  // by parts, the identity behind eqs. (38)-(39)); checked via the RHS pieces.
  Sys sys(400, params(true, 0.0, true));
  auto y = disturbed_state(sys, 8, 0.04);
  std::vector<Real> ydot(y.size());
  ASSERT_EQ(sys.rhs(0, y.data(), ydot.data()), 0);
  const StateLayout& L = sys.layout();
  const auto v = vector_field<2>(y.data(), L, Field::Velocity);
  const auto dv = vector_field<2>(ydot.data(), L, Field::Velocity);
  const auto rho = scalar_field(y.data(), L, Field::Density);
  const auto psi = scalar_field(y.data(), L, Field::Psi);
  const Real m = sys.params().mass;
  Real lhs = 0, rhs = 0, scale = 0;
  for (Index a = 0; a < v.cols(); ++a) {
    lhs += m / rho[a] * psi[a] * sys.div_v(0, y.data())[a];
    rhs += m * v.col(a).dot(dv.col(a));  // dv = -grad psi / rho
    scale += std::abs(m / rho[a] * psi[a] * sys.div_v(0, y.data())[a]);
  }
  EXPECT_NEAR(lhs, rhs, 1e-12 * scale);
}
