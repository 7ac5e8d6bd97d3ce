// Exact properties of the conjugate cleaning pair of operators/conjugate_cleaning.hpp (seed 000,
// §II-C), in 2D and 3D, on random particle clusters (random h, rho, Omega, B, psi):
//  - the difference divergence (20): by hand, and exactly 0 for a uniform field;
//  - the symmetric gradient (23) is the conjugate of (20): eq. (22),
//      sum_a m_a/rho_a B_a . (dB_a/dt)_psi = sum_a m_a/rho_a psi_a (div B)_a,
//    to round-off, so that with dpsi/dt = -c_h^2 div B the energy (21) is conserved, with the
//    gradients as vectors and as RadialGradient (the form the SPMHD loop uses);
//  - the difference gradient is not the conjugate (the identity fails by O(1));
//  - RadialGradient computes the symmetric gradient as (m (q_a F_a + q_b F_b)) x_ab.
#include <gtest/gtest.h>

#include "random_cluster.hpp"
#include "sphark/operators/conjugate_cleaning.hpp"

namespace sphark {
namespace {

using test::Cluster;
using test::random_cluster;
using test::RoundOffSum;

TEST(ConjugateCleaning, DifferenceDivergenceByHandAndForAUniformField) {
  // 2 [(1, 2) - (0, 1)] . (1/2, -1) = 2 (1/2 - 1) = -1
  EXPECT_EQ(difference_divergence_term(2.0, Vec<2>(1, 2), Vec<2>(0, 1), Vec<2>(0.5, -1)), -1.0);
  const Cluster<3> c = random_cluster<3>(20, 1);
  const Vec<3> A(0.3, -1.7, 2.2);
  for (std::size_t a = 0; a < c.size(); ++a) {
    Real sum = 0;
    for (std::size_t b = 0; b < c.size(); ++b)
      if (b != a) sum += difference_divergence_term(c.m[b], A, A, test::pair_of<CubicSpline<3>>(c, a, b).g_a);
    EXPECT_EQ(sum, 0.0);
  }
}

enum class GradPsi { Symmetric, SymmetricRadial, Difference };

// Both sides of eq. (22) and the sum of the magnitudes of their terms.
template <int D, class K>
std::pair<Real, Real> eq22_sides(const Cluster<D>& c, GradPsi form, Real& scale) {
  Real lhs = 0, rhs = 0;
  scale = 0;
  for (std::size_t a = 0; a < c.size(); ++a) {
    Vec<D> grad = Vec<D>::Zero();
    Real div = 0;
    const Real q_a = c.psi[a] * c.o(a);  // psi / (Omega rho^2)
    for (std::size_t b = 0; b < c.size(); ++b) {
      if (a == b) continue;
      const auto p = test::pair_of<K>(c, a, b);
      const Real q_b = c.psi[b] * c.o(b);
      div += difference_divergence_term(c.m[b], c.B[a].template head<D>(), c.B[b].template head<D>(), p.g_a);
      if (form == GradPsi::Symmetric) grad += symmetric_gradient_term(c.m[b], q_a, p.g_a, q_b, p.g_b);
      if (form == GradPsi::SymmetricRadial)
        grad += symmetric_gradient_term(c.m[b], q_a, p.radial_a(), q_b, p.radial_b()).vector();
      if (form == GradPsi::Difference) grad += difference_gradient_term(c.m[b], c.psi[a], c.psi[b], p.g_a);
    }
    const Real inv_omega_rho = 1 / (c.omega[a] * c.rho[a]);
    // (23): dB/dt = -rho_a sum; the difference form: dB/dt = -grad psi = -(1/(Omega rho)) sum
    const Vec<D> dB = form == GradPsi::Difference ? Vec<D>(-inv_omega_rho * grad) : Vec<D>(-c.rho[a] * grad);
    const Real div_b = -inv_omega_rho * div;  // (20)
    const Real l = c.m[a] / c.rho[a] * c.B[a].template head<D>().dot(dB), r = c.m[a] / c.rho[a] * c.psi[a] * div_b;
    lhs += l;
    rhs += r;
    scale += std::abs(l) + std::abs(r);
  }
  return {lhs, rhs};
}

template <int D, class K>
void check_conjugacy() {
  const Cluster<D> c = random_cluster<D>(40, 7 + D);
  Real scale = 0;
  for (GradPsi form : {GradPsi::Symmetric, GradPsi::SymmetricRadial}) {
    const auto [lhs, rhs] = eq22_sides<D, K>(c, form, scale);
    ASSERT_GT(scale, 0);
    EXPECT_LT(std::abs(lhs - rhs), 1e-14 * scale) << "D=" << D << " lhs " << lhs << " rhs " << rhs;
    // (21): B . dB/rho + psi dpsi/(rho c_h^2) with dpsi/dt = -c_h^2 div B is lhs - rhs.
  }
  const auto [lhs, rhs] = eq22_sides<D, K>(c, GradPsi::Difference, scale);
  EXPECT_GT(std::abs(lhs - rhs), 1e-3 * scale) << "the difference gradient is not conjugate to (20)";
}

TEST(ConjugateCleaning, SymmetricGradientIsTheConjugateOfTheDifferenceDivergence) {
  check_conjugacy<2, CubicSpline<2>>();
  check_conjugacy<3, CubicSpline<3>>();
  check_conjugacy<2, WendlandC2<2>>();
  check_conjugacy<3, QuinticSpline<3>>();
}

TEST(ConjugateCleaning, RadialGradientCombinesTheScalarsFirst) {
  const Vec<3> x_ab(0.3, -0.2, 0.7);
  const RadialGradient<3> g_a{-1.25, x_ab}, g_b{-0.75, x_ab};
  const Real m = 1.5, q_a = 0.2, q_b = -0.4;
  const Vec<3> radial = symmetric_gradient_term(m, q_a, g_a, q_b, g_b).vector();
  EXPECT_EQ(radial, Vec<3>((m * (q_a * -1.25 + q_b * -0.75)) * x_ab));
  const Vec<3> vectors = symmetric_gradient_term(m, q_a, g_a.vector(), q_b, g_b.vector());
  const Real scale = m * (std::abs(q_a * -1.25) + std::abs(q_b * -0.75)) * x_ab.norm();  // (the sum cancels)
  EXPECT_LT((radial - vectors).norm(), 1e-15 * scale);
  // the difference gradient: (m (f_b - f_a) F) x_ab
  EXPECT_EQ(difference_gradient_term(m, 1.0, 3.0, g_a).vector(), Vec<3>((m * 2.0 * -1.25) * x_ab));
}

}  // namespace
}  // namespace sphark
