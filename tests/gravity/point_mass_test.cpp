// Sink (point-mass) gravity: the softened pair forms against their analytic forms, equal and
// opposite sink-gas and sink-sink forces (momentum to round-off), the returned energy against
// the pair sum, and thread-count independence.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <vector>

#include "gravity_test_support.hpp"
#include "sphark/gravity/point_mass_gravity.hpp"
#include "sphark/gravity/sphere_particles.hpp"

using namespace sphark;

namespace {

constexpr SinkSoftening kPlummer{PointMassSoftening::Plummer, 0.05};
constexpr SinkSoftening kKernel{PointMassSoftening::Kernel, 0.05};

struct Sinks {
  std::vector<Real> x{0.1, -0.2, 0.05, -0.4, 0.3, 0.0, 0.02, 0.01, -0.03}, m{0.3, 0.1, 0.05};
  PointMasses view() const { return {x.data(), m.data(), m.size()}; }
};

}  // namespace

TEST(PointMassPair, PlummerAndNewtonianForms) {
  const Real eps = kPlummer.length;
  for (Real r : {0.0, 0.01, 0.05, 0.2, 3.0}) {
    const PairGravity p = point_mass_pair(kPlummer, r * r);
    EXPECT_DOUBLE_EQ(p.phi, -1 / std::sqrt(r * r + eps * eps));
    EXPECT_DOUBLE_EQ(p.force_over_r, std::pow(r * r + eps * eps, -1.5));
    if (r > 0) {
      const PairGravity n = point_mass_pair(SinkSoftening{}, r * r);
      EXPECT_DOUBLE_EQ(n.phi, -1 / r);
      EXPECT_DOUBLE_EQ(n.force_over_r, 1 / (r * r * r));
      const Real d = 1e-6;  // force = -d phi / dr
      const Real dphi = (point_mass_pair(kPlummer, (r + d) * (r + d)).phi - point_mass_pair(kPlummer, (r - d) * (r - d)).phi) / (2 * d);
      EXPECT_NEAR(p.force_over_r * r, dphi, 1e-7 * std::abs(dphi));
    }
  }
}

TEST(PointMassPair, KernelSofteningIsThePm07FormWithHEqualEps) {
  using S = KernelSoftening<CubicSpline<3>>;
  for (Real r : {0.0, 0.02, 0.05, 0.08, 0.1, 0.5}) {
    const PairGravity p = point_mass_pair(kKernel, r * r);
    EXPECT_NEAR(p.phi, S::phi(r, kKernel.length), 1e-12 * std::abs(p.phi));
    EXPECT_NEAR(p.force_over_r, S::force_over_r(r, kKernel.length), 1e-12 * p.force_over_r);
  }
  EXPECT_DOUBLE_EQ(point_mass_pair(kKernel, 0.25).phi, -2.0);  // r = 0.5 > 2 eps: Newtonian
}

TEST(SinkGasGravity, EqualAndOppositeForcesAndPairEnergy) {
  const SphereParticles gas = random_sphere(SphereProfile::Uniform, 3000, 1, 1, 1.2, 5);
  const Sinks sinks;
  for (const SinkSoftening& soft : {SinkSoftening{}, kPlummer, kKernel}) {
    std::vector<Real> gas_acc(3 * gas.size(), 0), gas_pot(gas.size(), 0), sink_acc(9, 0), sink_pot(3, 0);
    SinkGasGravity<> sg;
    const Real G = 0.7;
    const Real e = sg.add(G, sinks.view(), gas.sources(), soft, gas_acc.data(), gas_pot.data(), sink_acc.data(),
                          sink_pot.data());
    // momentum: gas and sinks together
    std::vector<Real> m = gas.m, acc = gas_acc;
    m.insert(m.end(), sinks.m.begin(), sinks.m.end());
    acc.insert(acc.end(), sink_acc.begin(), sink_acc.end());
    EXPECT_LT(gravity_test::momentum_error(m, acc), 1e-14);
    // the energy is the pair sum, and (1/2) sum m Phi over gas and sinks
    Real pairs = 0, half = 0;
    for (std::size_t a = 0; a < gas.size(); ++a) {
      half += 0.5 * gas.m[a] * gas_pot[a];
      for (std::size_t s = 0; s < 3; ++s) {
        Real r2 = 0;
        for (int c = 0; c < 3; ++c) r2 += (gas.x[3 * a + c] - sinks.x[3 * s + c]) * (gas.x[3 * a + c] - sinks.x[3 * s + c]);
        pairs += G * gas.m[a] * sinks.m[s] * point_mass_pair(soft, r2).phi;
      }
    }
    for (std::size_t s = 0; s < 3; ++s) half += 0.5 * sinks.m[s] * sink_pot[s];
    EXPECT_NEAR(e, pairs, 1e-13 * std::abs(pairs));
    EXPECT_NEAR(e, half, 1e-13 * std::abs(pairs));
    EXPECT_EQ(sg.allocations(), 1);
  }
}

TEST(SinkGasGravity, IndependentOfThreadCount) {
  const SphereParticles gas = random_sphere(SphereProfile::InverseR, 5000, 1, 1, 1.2, 6);
  const Sinks sinks;
  std::vector<std::vector<Real>> results;
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    std::vector<Real> gas_acc(3 * gas.size(), 0), sink_acc(9, 0);
    SinkGasGravity<> sg;
    const Real e = sg.add(1, sinks.view(), gas.sources(), kKernel, gas_acc.data(), nullptr, sink_acc.data(), nullptr);
    gas_acc.insert(gas_acc.end(), sink_acc.begin(), sink_acc.end());
    gas_acc.push_back(e);
    results.push_back(gas_acc);
  }
  omp_set_num_threads(1);
  EXPECT_EQ(results[0], results[1]);
}

TEST(SinkSinkGravity, EqualAndOppositeAndEnergy) {
  const Sinks sinks;
  std::vector<Real> acc(9, 0), pot(3, 0);
  const Real e = add_sink_sink_gravity(2.0, sinks.view(), kPlummer, acc.data(), pot.data());
  EXPECT_LT(gravity_test::momentum_error(sinks.m, acc), 1e-15);
  Real pairs = 0, half = 0;
  for (int i = 0; i < 3; ++i) {
    half += 0.5 * sinks.m[i] * pot[i];
    for (int j = i + 1; j < 3; ++j) {
      Real r2 = 0;
      for (int c = 0; c < 3; ++c) r2 += (sinks.x[3 * i + c] - sinks.x[3 * j + c]) * (sinks.x[3 * i + c] - sinks.x[3 * j + c]);
      pairs += 2.0 * sinks.m[i] * sinks.m[j] * point_mass_pair(kPlummer, r2).phi;
    }
  }
  EXPECT_NEAR(e, pairs, 1e-15 * std::abs(pairs));
  EXPECT_NEAR(e, half, 1e-15 * std::abs(pairs));
  // a single unsoftened pair: |a_0| = G m_1 / r^2
  std::vector<Real> two(6, 0);
  const PointMasses p{sinks.x.data(), sinks.m.data(), 2};
  add_sink_sink_gravity(1.0, p, SinkSoftening{}, two.data(), nullptr);
  Real r2 = 0;
  for (int c = 0; c < 3; ++c) r2 += (sinks.x[c] - sinks.x[3 + c]) * (sinks.x[c] - sinks.x[3 + c]);
  EXPECT_NEAR(std::hypot(two[0], two[1], two[2]), sinks.m[1] / r2, 1e-14 * sinks.m[1] / r2);
}

TEST(SinkGravity, RejectsSofteningWithoutLength) {
  const Sinks sinks;
  std::vector<Real> acc(9, 0);
  EXPECT_THROW(add_sink_sink_gravity(1.0, sinks.view(), SinkSoftening{PointMassSoftening::Plummer, 0}, acc.data(), nullptr),
               std::invalid_argument);
}
