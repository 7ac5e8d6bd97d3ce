// The 3D instantiations of the WCSPH scheme run (issue #14, item 11): on a disturbed cubic
// lattice with random velocities and densities,
//  - total momentum is conserved to round-off with viscosity, density diffusion and cleaning on;
//  - without dissipation the energy E = sum m (v^2/2 + u(rho)) of the Tait EOS (26) is conserved
//    by the semi-discrete equations: dE/dt = sum m v.dv/dt + sum m P/rho^2 drho/dt = 0 (the
//    pressure force (27) and the continuity equation (28) are conjugate), to round-off;
//  - a uniform compressed state at rest on the lattice: the interior particles (beyond the
//    support from every face) feel no force, to round-off of the edge particles' force.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sphark/kernels/kernels.hpp"
#include "sphark/operators/tait_eos.hpp"
#include "sphark/schemes/wcsph/wcsph_system.hpp"

using namespace sphark;

namespace {
constexpr int kSide = 8;
constexpr Real kDx = 0.05;

template <class K>
WcsphParams<3> params3(Real alpha, Real delta, bool cleaning) {
  WcsphParams<3> p;
  p.mass = 1000 * kDx * kDx * kDx;
  p.h = 1.3 * kDx;
  p.alpha = alpha;
  p.delta = delta;
  p.cleaning = cleaning;
  return p;
}

template <class K>
std::vector<Real> disturbed_cube(const WcsphSystem<3, K>& sys, unsigned seed, Real jitter, Real speed) {
  const StateLayout& L = sys.layout();
  std::vector<Real> y(L.size());
  auto x = vector_field<3>(y.data(), L, Field::Position);
  auto v = vector_field<3>(y.data(), L, Field::Velocity);
  auto rho = scalar_field(y.data(), L, Field::Density);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<Real> u(-1, 1);
  for (std::size_t a = 0; a < L.particles(); ++a) {
    const Vec<3> lattice(a % kSide, a / kSide % kSide, a / (kSide * kSide));
    x.col(a) = kDx * lattice + jitter * kDx * Vec<3>(u(rng), u(rng), u(rng));
    v.col(a) = speed * Vec<3>(u(rng), u(rng), u(rng));
    rho[a] = 1000 * (1 + (speed > 0 ? 0.01 * u(rng) : 0.0));
  }
  if (L.has(Field::Psi))
    for (Index a = 0; a < static_cast<Index>(L.particles()); ++a) y[L.offset(Field::Psi) + a] = 1e4 * u(rng);
  return y;
}

template <class K>
void expect_momentum_conserved() {
  WcsphSystem<3, K> sys(kSide * kSide * kSide, params3<K>(0.1, 0.1, true));
  const std::vector<Real> y = disturbed_cube(sys, 5, 0.2, 1.0);
  std::vector<Real> ydot(y.size());
  ASSERT_EQ(sys.rhs(0, y.data(), ydot.data()), 0) << sys.last_error();
  const auto dv = vector_field<3>(ydot.data(), sys.layout(), Field::Velocity);
  Vec<3> total = Vec<3>::Zero();
  Real scale = 0;
  for (Index a = 0; a < dv.cols(); ++a) {
    total += sys.params().mass * dv.col(a);
    scale += sys.params().mass * dv.col(a).norm();
  }
  ASSERT_GT(scale, 0);
  EXPECT_LT(total.norm(), 1e-13 * scale) << K::name;
}

template <class K>
void expect_energy_conserved() {
  WcsphSystem<3, K> sys(kSide * kSide * kSide, params3<K>(0, 0, false));
  const std::vector<Real> y = disturbed_cube(sys, 7, 0.2, 1.0);
  std::vector<Real> ydot(y.size());
  ASSERT_EQ(sys.rhs(0, y.data(), ydot.data()), 0) << sys.last_error();
  const StateLayout& L = sys.layout();
  const auto v = vector_field<3>(y.data(), L, Field::Velocity);
  const auto dv = vector_field<3>(ydot.data(), L, Field::Velocity);
  const auto rho = scalar_field(y.data(), L, Field::Density);
  const auto drho = scalar_field(ydot.data(), L, Field::Density);
  const WcsphParams<3>& p = sys.params();
  Real rate = 0, scale = 0;
  for (Index a = 0; a < v.cols(); ++a) {
    const Real kinetic = p.mass * v.col(a).dot(dv.col(a));
    const Real thermal = p.mass * tait_pressure(rho[a], p.rho0, p.sound_speed) / (rho[a] * rho[a]) * drho[a];  // du/dt
    rate += kinetic + thermal;
    scale += std::abs(kinetic) + std::abs(thermal);
  }
  ASSERT_GT(scale, 0);
  EXPECT_LT(std::abs(rate), 1e-12 * scale) << K::name;
}
}  // namespace

TEST(Wcsph3D, ConservesMomentumToRoundOff) {
  expect_momentum_conserved<CubicSpline<3>>();
  expect_momentum_conserved<WendlandC2<3>>();
  expect_momentum_conserved<WendlandC4<3>>();
}

TEST(Wcsph3D, ConservesEnergyWithoutDissipationToRoundOff) {
  expect_energy_conserved<CubicSpline<3>>();
  expect_energy_conserved<WendlandC2<3>>();
  expect_energy_conserved<WendlandC4<3>>();
}

TEST(Wcsph3D, UniformStateAtRestHasNoInteriorForce) {
  using K = WendlandC2<3>;
  WcsphSystem<3, K> sys(kSide * kSide * kSide, params3<K>(0.1, 0.1, false));
  std::vector<Real> y = disturbed_cube(sys, 1, 0.0, 0.0);  // the lattice at rest
  const StateLayout& L = sys.layout();
  for (std::size_t a = 0; a < L.particles(); ++a) y[L.offset(Field::Density) + a] = 1010;  // P > 0
  std::vector<Real> ydot(y.size());
  ASSERT_EQ(sys.rhs(0, y.data(), ydot.data()), 0);
  const auto x = vector_field<3>(y.data(), L, Field::Position);
  const auto dv = vector_field<3>(ydot.data(), L, Field::Velocity);
  const Real reach = K::support * sys.params().h, far = (kSide - 1) * kDx;
  Real edge = 0, interior = 0;
  int interior_count = 0;
  for (Index a = 0; a < dv.cols(); ++a) {
    const bool inside = (x.col(a).array() >= reach).all() && (x.col(a).array() <= far - reach).all();
    (inside ? interior : edge) = std::max(inside ? interior : edge, dv.col(a).norm());
    interior_count += inside;
  }
  ASSERT_GT(interior_count, 0);
  ASSERT_GT(edge, 0);  // the free surface pushes outwards
  EXPECT_LT(interior, 1e-12 * edge);
}
