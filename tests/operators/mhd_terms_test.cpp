// Exact properties of the SPMHD pair terms of operators/mhd_operators.hpp (seed 000, §II), each
// on its own, in 2D and 3D, on random particle clusters (random h, rho, Omega, P, v, B: the
// identities are algebraic and hold for any values):
//  - eq. (8): the stress block by hand;
//  - eq. (6): antisymmetric pair by pair (bit for bit), total momentum conserved to round-off;
//  - eq. (9): for a uniform field it removes exactly the tension part of (6), leaving the
//    isotropic pressure force of P + B^2/2;
//  - eq. (7) with (6) and the P dV work: the energy identity (kinetic + magnetic + thermal,
//    with the summation density's drho/dt) to round-off; one pair by hand;
//  - eq. (10): the field sum sum_a m_a dB_a/dt / rho_a and the total energy conserved to
//    round-off, heating >= 0 pair by pair;
//  - eqs. (19)+(25): by hand; the (25) term balances the density change of the psi energy.
#include <gtest/gtest.h>

#include "random_cluster.hpp"
#include "sphark/operators/mhd_operators.hpp"
#include "sphark/operators/pressure_force.hpp"

namespace sphark {
namespace {

using test::Cluster;
using test::random_cluster;
using test::RoundOffSum;
using Vec3 = mhd::Vec3;
using K2 = CubicSpline<2>;
using K3 = CubicSpline<3>;
template <int D>
using MatD = Eigen::Matrix<Real, D, D>;

template <int D>
MatD<D> stress(const Cluster<D>& c, std::size_t a, const Vec3& B) {
  MatD<D> S;
  mhd::maxwell_stress_over_omega_rho2<D>(B.data(), c.P[a], c.o(a), S.data());
  return S;
}

template <int D>
void check_stress_by_hand() {
  const Vec3 B(1, 2, 2);  // B^2 = 9, P = 0.5: P + B^2/2 = 5; o = 2
  MatD<D> S;
  mhd::maxwell_stress_over_omega_rho2<D>(B.data(), 0.5, 2.0, S.data());
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) EXPECT_EQ(S(i, j), 2 * (B[i] * B[j] - (i == j ? 5 : 0))) << i << j;
  EXPECT_EQ(S(0, 0), -8.0);
  EXPECT_EQ(S(0, 1), 4.0);
}

TEST(MhdTerms, MaxwellStressBlockIsEq8) {
  check_stress_by_hand<2>();
  check_stress_by_hand<3>();
}

template <int D, class K>
void check_force_antisymmetric_and_momentum() {
  const Cluster<D> c = random_cluster<D>(40, 5 + D);
  Vec<D> total = Vec<D>::Zero();
  Real scale = 0;
  for (std::size_t a = 0; a < c.size(); ++a)
    for (std::size_t b = 0; b < c.size(); ++b) {
      if (a == b) continue;
      const auto ab = test::pair_of<K>(c, a, b), ba = test::pair_of<K>(c, b, a);
      const Vec<D> f_ab = mhd::maxwell_force_term(1.0, stress(c, a, c.B[a]), ab.g_a, stress(c, b, c.B[b]), ab.g_b);
      const Vec<D> f_ba = mhd::maxwell_force_term(1.0, stress(c, b, c.B[b]), ba.g_a, stress(c, a, c.B[a]), ba.g_b);
      EXPECT_EQ(f_ab, Vec<D>(-f_ba));  // per unit mass product: antisymmetric bit for bit
      const Vec<D> f =
          c.m[a] * mhd::maxwell_force_term(c.m[b], stress(c, a, c.B[a]), ab.g_a, stress(c, b, c.B[b]), ab.g_b);
      total += f;
      scale += f.norm();
    }
  ASSERT_GT(scale, 0);
  EXPECT_LT(total.norm(), 1e-14 * scale) << total.transpose();
}

TEST(MhdTerms, MaxwellForceIsAntisymmetricAndConservesMomentum) {
  check_force_antisymmetric_and_momentum<2, K2>();
  check_force_antisymmetric_and_momentum<3, K3>();
  check_force_antisymmetric_and_momentum<2, WendlandC4<2>>();
}

template <int D, class K>
void check_monopole_removes_tension() {
  const Cluster<D> c = random_cluster<D>(30, 17 + D);
  const Vec3 B(0.7, -0.4, D == 2 ? 0.2 : 0.5);  // uniform
  for (std::size_t a = 0; a < c.size(); ++a) {
    Vec<D> force = Vec<D>::Zero(), pressure_only = Vec<D>::Zero();
    Real monopole = 0, scale = 0;
    for (std::size_t b = 0; b < c.size(); ++b) {
      if (a == b) continue;
      const auto p = test::pair_of<K>(c, a, b);
      force += mhd::maxwell_force_term(c.m[b], stress(c, a, B), p.g_a, stress(c, b, B), p.g_b);
      const Vec<D> oB_a = c.o(a) * B.head<D>(), oB_b = c.o(b) * B.head<D>();
      monopole += mhd::monopole_term(c.m[b], oB_a, p.g_a, oB_b, p.g_b);
      const Real pt_a = c.P[a] + 0.5 * B.squaredNorm(), pt_b = c.P[b] + 0.5 * B.squaredNorm();
      pressure_only -= c.m[b] * (c.o(a) * pt_a * p.g_a + c.o(b) * pt_b * p.g_b);
      scale += c.m[b] * (c.o(a) * p.g_a.norm() + c.o(b) * p.g_b.norm()) * (pt_a + B.squaredNorm());
    }
    mhd::subtract_monopole_force<D>(force, B, monopole);
    EXPECT_LT((force - pressure_only).norm(), 1e-14 * scale) << "particle " << a;
  }
}

TEST(MhdTerms, MonopoleSubtractionRemovesTheTensionOfAUniformField) {
  check_monopole_removes_tension<2, K2>();
  check_monopole_removes_tension<3, K3>();
}

// d/dt sum_a m_a (v_a^2/2 + u_a + B_a^2/(2 rho_a)) with dv from (6), dB from (7), du = the P dV
// work P_a/(Omega_a rho_a^2) sum_b m_b v_ab . g_a and drho_a/dt = (1/Omega_a) sum_b m_b v_ab . g_a.
template <int D, class K>
void check_induction_energy_identity() {
  const Cluster<D> c = random_cluster<D>(40, 29 + D);
  RoundOffSum rate;
  for (std::size_t a = 0; a < c.size(); ++a) {
    Vec<D> dv = Vec<D>::Zero();
    mhd::Induction<D> induction;
    Real continuity = 0;
    for (std::size_t b = 0; b < c.size(); ++b) {
      if (a == b) continue;
      const auto p = test::pair_of<K>(c, a, b);
      const Vec<D> v_ab = c.v[a] - c.v[b];
      dv += mhd::maxwell_force_term(c.m[b], stress(c, a, c.B[a]), p.g_a, stress(c, b, c.B[b]), p.g_b);
      induction.pair(c.m[b], v_ab, c.B[a], p.g_a);
      continuity += continuity_term<D>(c.m[b], v_ab, p.g_a);
    }
    const Real inv_omega_rho = 1 / (c.omega[a] * c.rho[a]);
    const Vec3 dB = induction.finish(inv_omega_rho);
    const Real drho = continuity / c.omega[a], du = c.P[a] * c.o(a) * continuity;
    rate.add(c.m[a] * c.v[a].dot(dv));
    rate.add(c.m[a] * du);
    rate.add(c.m[a] * c.B[a].dot(dB) / c.rho[a]);
    rate.add(-c.m[a] * c.B[a].squaredNorm() / (2 * c.rho[a] * c.rho[a]) * drho);
  }
  ASSERT_GT(rate.scale, 0);
  EXPECT_LT(std::abs(rate.sum), 1e-14 * rate.scale) << rate.sum << " of " << rate.scale;
}

TEST(MhdTerms, InductionAndMaxwellForceConserveEnergy) {
  check_induction_energy_identity<2, K2>();
  check_induction_energy_identity<3, K3>();
  check_induction_energy_identity<3, QuinticSpline<3>>();
}

TEST(MhdTerms, InductionOfOnePairByHand) {
  // m_b = 2, v_ab = (1, 0), B_a = (0, 1, 1/2), g_a = (1/2, 1/4): B.g = 1/4, v.g = 1/2:
  // sum = 2 [(1/4)(1, 0, 0) - (1/2)(0, 1, 1/2)] = (1/2, -1, -1/2); times -1/(Omega rho) = -1/2.
  mhd::Induction<2> induction;
  induction.pair(2.0, Vec<2>(1, 0), Vec3(0, 1, 0.5), Vec<2>(0.5, 0.25));
  EXPECT_EQ(induction.sum, Vec3(0.5, -1, -0.5));
  EXPECT_EQ(induction.finish(0.5), Vec3(-0.25, 0.5, 0.25));
}

template <int D, class K>
void check_resistivity_conserves_field_and_energy() {
  const Cluster<D> c = random_cluster<D>(40, 41 + D);
  const Real alpha_b = 1;
  Vec3 field = Vec3::Zero();
  Real field_scale = 0;
  RoundOffSum energy;
  for (std::size_t a = 0; a < c.size(); ++a) {
    Vec3 sum = Vec3::Zero();
    Real du = 0;
    for (std::size_t b = 0; b < c.size(); ++b) {
      if (a == b) continue;
      const auto p = test::pair_of<K>(c, a, b);
      const Vec<D> v_ab = c.v[a] - c.v[b], rhat = p.x_ab / p.r;
      const Real rhat_dot_gbar = 0.5 * (p.F_a + p.F_b) * p.r;
      const Real inv_rho_ab = 1 / (0.5 * (c.rho[a] + c.rho[b]));
      const mhd::ResistivePairTerm t = mhd::resistivity_term<D>(c.m[b], alpha_b, v_ab, v_ab.dot(rhat), rhat, inv_rho_ab,
                                                                Vec3(c.B[a] - c.B[b]), rhat_dot_gbar);
      EXPECT_GE(t.du_dt, 0.0);  // dissipation only heats
      sum += t.dB_dt;
      du += t.du_dt;
    }
    const Vec3 dB = c.rho[a] * sum;  // finish: times rho_a
    field += c.m[a] / c.rho[a] * dB;
    field_scale += c.m[a] / c.rho[a] * dB.norm();
    energy.add(c.m[a] * c.B[a].dot(dB) / c.rho[a]);
    energy.add(c.m[a] * du);
  }
  ASSERT_GT(field_scale, 0);
  EXPECT_LT(field.norm(), 1e-14 * field_scale);
  EXPECT_LT(std::abs(energy.sum), 1e-14 * energy.scale) << energy.sum << " of " << energy.scale;
}

TEST(MhdTerms, ResistivityConservesFieldSumAndEnergyAndOnlyHeats) {
  check_resistivity_conserves_field_and_energy<2, K2>();
  check_resistivity_conserves_field_and_energy<3, K3>();
}

TEST(MhdTerms, PsiRateByHand) {
  // -4 (1/2) - (1/4) 2 + (1/2) 2 (1/2) 3 = -2 - 1/2 + 3/2 = -1
  EXPECT_EQ(mhd::psi_rate(4, 0.5, 2, true, 0.25, true, 0.5, 3), -1.0);
  EXPECT_EQ(mhd::psi_rate(4, 0.5, 2, false, 0.25, true, 0.5, 3), -0.5);   // no damping
  EXPECT_EQ(mhd::psi_rate(4, 0.5, 2, true, 0.25, false, 0.5, 3), -2.5);   // no (25) term
}

TEST(MhdTerms, Eq25BalancesTheDensityChangeOfThePsiEnergy) {
  // e = m psi^2 / (2 rho c^2): de/dt = m [psi dpsi/dt / (rho c^2) - psi^2 / (2 rho^2 c^2) drho/dt]
  // = 0 for dpsi/dt from (25) alone, with drho/dt = (1/Omega) sum_b m_b v_ab . g_a.
  const Cluster<2> c = random_cluster<2>(20, 3);
  for (std::size_t a = 0; a < c.size(); ++a) {
    const Real c2 = 1.7, continuity = 0.3 + c.u[a], m = c.m[a], rho = c.rho[a], psi = c.psi[a];
    const Real dpsi = mhd::psi_rate(c2, 0, psi, false, 0, true, 1 / (c.omega[a] * rho), continuity);
    const Real gain = m * psi * dpsi / (rho * c2);
    const Real loss = m * psi * psi / (2 * rho * rho * c2) * continuity / c.omega[a];
    EXPECT_NEAR(gain, loss, 1e-15 * std::abs(loss)) << a;
  }
}

}  // namespace
}  // namespace sphark
