// Exact properties of the signal-velocity dissipation of operators/signal_velocity_dissipation.hpp
// (Monaghan 1997 viscosity, Price 2008 conductivity), in 2D and 3D on random particle clusters:
//  - viscosity: by hand; antisymmetric pair by pair (bit for bit); momentum and total energy
//    (kinetic + heating) conserved to round-off; heating >= 0;
//  - conductivity: total thermal energy conserved to round-off, heat flows from hot to cold.
#include <gtest/gtest.h>

#include "random_cluster.hpp"
#include "sphark/operators/signal_velocity_dissipation.hpp"

namespace sphark {
namespace {

using test::Cluster;
using test::random_cluster;
using test::RoundOffSum;

// What both terms need about the pair (a, b).
template <int D>
struct DissipationPair {
  Vec<D> rhat;
  Real w, rhat_dot_gbar, inv_rho_ab;
};

template <int D, class K>
DissipationPair<D> dissipation_pair(const Cluster<D>& c, std::size_t a, std::size_t b) {
  const auto p = test::pair_of<K>(c, a, b);
  const Vec<D> rhat = p.x_ab / p.r;
  return {rhat, (c.v[a] - c.v[b]).dot(rhat), 0.5 * (p.F_a + p.F_b) * p.r,
          1 / (0.5 * (c.rho[a] + c.rho[b]))};
}

TEST(Dissipation, ViscosityByHand) {
  // alpha = 1, beta = 2, c = 1, w = -1: v_sig = 3, Pi = 3; rhat . gbar = -1:
  // dv = -m Pi (rhat . gbar) rhat = (3, 0) (a pushed away from b), du = m Pi w (rhat . gbar) / 2 = 3/2.
  const ViscousPairTerm<2> t = signal_velocity_viscosity_term<2>(1, 1, 2, 1, 1, -1, 1, Vec<2>(1, 0), -1);
  EXPECT_EQ(t.dv_dt, Vec<2>(3, 0));
  EXPECT_EQ(t.du_dt, 1.5);
  EXPECT_TRUE(approaching(-1e-300));
  EXPECT_FALSE(approaching(0.0));
}

template <int D, class K>
void check_viscosity() {
  const Cluster<D> c = random_cluster<D>(40, 13 + D);
  const Real alpha = 1, beta = 2;
  Vec<D> momentum = Vec<D>::Zero();
  Real momentum_scale = 0;
  RoundOffSum energy;
  std::size_t approaching_pairs = 0;
  for (std::size_t a = 0; a < c.size(); ++a)
    for (std::size_t b = 0; b < c.size(); ++b) {
      if (a == b) continue;
      const auto ab = dissipation_pair<D, K>(c, a, b), ba = dissipation_pair<D, K>(c, b, a);
      EXPECT_EQ(ab.w, ba.w);
      if (!approaching(ab.w)) continue;
      ++approaching_pairs;
      // c.P stands in for the signal speeds c_a, c_b
      const auto t_ab = signal_velocity_viscosity_term<D>(1.0, alpha, beta, c.P[a], c.P[b], ab.w, ab.inv_rho_ab,
                                                          ab.rhat, ab.rhat_dot_gbar);
      const auto t_ba = signal_velocity_viscosity_term<D>(1.0, alpha, beta, c.P[b], c.P[a], ba.w, ba.inv_rho_ab,
                                                          ba.rhat, ba.rhat_dot_gbar);
      EXPECT_EQ(t_ab.dv_dt, Vec<D>(-t_ba.dv_dt));
      EXPECT_EQ(t_ab.du_dt, t_ba.du_dt);
      EXPECT_GE(t_ab.du_dt, 0.0);
      const auto t = signal_velocity_viscosity_term<D>(c.m[b], alpha, beta, c.P[a], c.P[b], ab.w, ab.inv_rho_ab,
                                                       ab.rhat, ab.rhat_dot_gbar);
      momentum += c.m[a] * t.dv_dt;
      momentum_scale += c.m[a] * t.dv_dt.norm();
      energy.add(c.m[a] * c.v[a].dot(t.dv_dt));
      energy.add(c.m[a] * t.du_dt);
    }
  ASSERT_GT(approaching_pairs, 100u);
  EXPECT_LT(momentum.norm(), 1e-14 * momentum_scale);
  EXPECT_LT(std::abs(energy.sum), 1e-14 * energy.scale) << energy.sum << " of " << energy.scale;
}

TEST(Dissipation, ViscosityIsAntisymmetricAndConservesMomentumAndEnergy) {
  check_viscosity<2, CubicSpline<2>>();
  check_viscosity<3, CubicSpline<3>>();
}

template <int D, class K>
void check_conductivity() {
  const Cluster<D> c = random_cluster<D>(40, 23 + D);
  RoundOffSum thermal;
  for (std::size_t a = 0; a < c.size(); ++a)
    for (std::size_t b = 0; b < c.size(); ++b) {
      if (a == b) continue;
      const auto p = dissipation_pair<D, K>(c, a, b);
      const Real du = conductivity_term(c.m[b], 1.0, c.P[a], c.P[b], c.u[a], c.u[b], p.inv_rho_ab, p.rhat_dot_gbar);
      if (c.u[a] > c.u[b]) {
        EXPECT_LE(du, 0.0);  // the hotter particle loses heat
      }
      thermal.add(c.m[a] * du);
    }
  ASSERT_GT(thermal.scale, 0);
  EXPECT_LT(std::abs(thermal.sum), 1e-14 * thermal.scale);
}

TEST(Dissipation, ConductivityConservesThermalEnergyAndFlowsFromHotToCold) {
  check_conductivity<2, CubicSpline<2>>();
  check_conductivity<3, CubicSpline<3>>();
}

}  // namespace
}  // namespace sphark
