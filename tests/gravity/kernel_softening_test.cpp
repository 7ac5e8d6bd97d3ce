// Kernel softening (Price & Monaghan 2007) for every 3D kernel: the defining property (the
// force is the enclosed kernel mass over r^2), force = -d(potential)/dr and dphi/dh against
// finite differences, continuity at the piece boundaries, exact Newtonian gravity outside the
// support, and the cubic spline against PM07's printed Appendix A forms.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "gravity_test_support.hpp"
#include "sphark/gravity/kernel_softening.hpp"

using namespace sphark;

namespace {

template <class K>
class KernelSofteningTest : public ::testing::Test {};
TYPED_TEST_SUITE(KernelSofteningTest, gravity_test::AllKernels);

constexpr Real kH = 0.7;  // a smoothing length that is not 1, so that every h scaling is exercised

// Separations from near 0 to 1.5 supports, avoiding none of the piece boundaries.
template <class K>
std::vector<Real> separations() {
  std::vector<Real> r;
  for (int i = 1; i <= 300; ++i) r.push_back(1.5 * K::support * kH * i / 300.0);
  return r;
}

// 4 pi int_0^r W(s, h) s^2 ds by composite Simpson on each piece (exact up to the rule's error).
template <class K>
Real enclosed_kernel_mass(Real r, Real h) {
  const auto& breaks = softening_detail::KernelPieces<K>::breaks;
  Real total = 0, lo = 0;
  for (std::size_t k = 1; k < breaks.size() && lo < r; ++k) {
    const Real hi = std::min(r, breaks[k] * h);
    const int n = 2000;
    const Real dx = (hi - lo) / n;
    Real s = 0;
    for (int i = 0; i <= n; ++i) {
      const Real x = lo + i * dx, f = K::w(x, h) * x * x;
      s += (i == 0 || i == n) ? f : (i % 2 ? 4 * f : 2 * f);
    }
    total += s * dx / 3;
    lo = hi;
  }
  return 4 * kPi * total;
}

}  // namespace

TYPED_TEST(KernelSofteningTest, PiecesAreTheKernelShape) {
  using K = TypeParam;
  using namespace softening_detail;
  const auto shapes = KernelPieces<K>::shapes();
  const auto& b = KernelPieces<K>::breaks;
  for (int k = 0; k < KernelPieces<K>::count; ++k)
    for (int i = 0; i < 50; ++i) {
      const Real q = b[k] + (b[k + 1] - b[k]) * (i + 0.5) / 50;
      Real f = 0;
      for (int j = kMaxTerms - 1; j >= 0; --j) f = f * q + shapes[k].c[j];
      EXPECT_NEAR(K::norm(1) * f, K::w(q, 1), 1e-13) << "q = " << q;
    }
}

TYPED_TEST(KernelSofteningTest, ForceIsEnclosedKernelMassOverRSquared) {
  using K = TypeParam;
  for (Real r : separations<K>()) {
    const Real expected = r < K::support * kH ? enclosed_kernel_mass<K>(r, kH) / (r * r) : 1 / (r * r);
    EXPECT_NEAR(KernelSoftening<K>::dphi_dr(r, kH), expected, 1e-10 * std::abs(expected)) << "r = " << r;
    EXPECT_NEAR(KernelSoftening<K>::force_over_r(r, kH) * r, KernelSoftening<K>::dphi_dr(r, kH),
                1e-13 * std::abs(expected));
  }
}

TYPED_TEST(KernelSofteningTest, ForceIsMinusPotentialDerivative) {
  using S = KernelSoftening<TypeParam>;
  const Real d = 1e-5 * kH;
  for (Real r : separations<TypeParam>()) {
    const Real numerical = (S::phi(r + d, kH) - S::phi(r - d, kH)) / (2 * d);
    EXPECT_NEAR(S::dphi_dr(r, kH), numerical, 1e-8 * std::max(1.0, S::dphi_dr(r, kH))) << "r = " << r;
  }
}

TYPED_TEST(KernelSofteningTest, DphiDhMatchesFiniteDifference) {
  using S = KernelSoftening<TypeParam>;
  const Real d = 1e-5 * kH;
  for (Real r : separations<TypeParam>()) {
    const Real numerical = (S::phi(r, kH + d) - S::phi(r, kH - d)) / (2 * d);
    EXPECT_NEAR(S::dphi_dh(r, kH), numerical, 1e-8) << "r = " << r;
  }
  EXPECT_NEAR(S::dphi_dh(0, kH), (S::phi(0, kH + d) - S::phi(0, kH - d)) / (2 * d), 1e-8);
}

TYPED_TEST(KernelSofteningTest, ContinuousAtPieceBoundariesAndSupport) {
  using K = TypeParam;
  using S = KernelSoftening<K>;
  const auto& b = softening_detail::KernelPieces<K>::breaks;
  for (std::size_t k = 1; k < b.size(); ++k) {
    const Real r = b[k] * kH, below = r * (1 - 1e-13), above = r * (1 + 1e-13);
    EXPECT_NEAR(S::phi(below, kH), S::phi(above, kH), 1e-11) << "q = " << b[k];
    EXPECT_NEAR(S::dphi_dr(below, kH), S::dphi_dr(above, kH), 1e-11) << "q = " << b[k];
    EXPECT_NEAR(S::dphi_dh(below, kH), S::dphi_dh(above, kH), 1e-11) << "q = " << b[k];
  }
}

TYPED_TEST(KernelSofteningTest, NewtonianOutsideTheSupport) {
  using K = TypeParam;
  using S = KernelSoftening<K>;
  for (Real q : {K::support, K::support + 1e-9, 2.5 * K::support, 40.0}) {
    const Real r = q * kH;
    EXPECT_EQ(S::phi(r, kH), -1 / r);
    EXPECT_EQ(S::dphi_dr(r, kH), 1 / (r * r));
    EXPECT_EQ(S::force_over_r(r, kH), 1 / (r * r * r));
    EXPECT_EQ(S::dphi_dh(r, kH), 0);
  }
  // and the softened potential lies above (is shallower than) the Newtonian one inside
  for (Real r : separations<K>()) {
    if (r < 0.99 * K::support * kH) {
      EXPECT_GT(S::phi(r, kH), -1 / r) << "r = " << r;
    }
  }
}

TYPED_TEST(KernelSofteningTest, PairIsSymmetricAndNewtonianBeyondBothSupports) {
  using K = TypeParam;
  for (Real r : separations<K>()) {
    const PairGravity ab = softened_pair<K>(r * r, kH, 0.6 * kH), ba = softened_pair<K>(r * r, 0.6 * kH, kH);
    EXPECT_EQ(ab.force_over_r, ba.force_over_r);
    EXPECT_EQ(ab.phi, ba.phi);
    // the fast combined evaluation (q = r * (1/h), one piece lookup) against the reference
    // functions (q = r / h): q differs by an ulp, amplified by the condition number of the
    // monomial form (up to ~1e2 for Wendland C6 near q = 2)
    using S = KernelSoftening<K>;
    const Real phi = 0.5 * (S::phi(r, kH) + S::phi(r, 0.6 * kH));
    const Real f = 0.5 * (S::force_over_r(r, kH) + S::force_over_r(r, 0.6 * kH));
    EXPECT_NEAR(ab.phi, phi, 1e-12 * std::abs(phi)) << "r = " << r;
    EXPECT_NEAR(ab.force_over_r, f, 1e-12 * std::abs(f)) << "r = " << r;
  }
  for (Real r : {K::support * kH, 3 * K::support * kH}) {  // beyond both supports: 1/r^3 and -1/r
    EXPECT_DOUBLE_EQ(softened_pair<K>(r * r, kH, 0.6 * kH).force_over_r, 1 / (r * r * r));
    EXPECT_DOUBLE_EQ(softened_pair<K>(r * r, kH, 0.6 * kH).phi, -1 / r);
  }
}

// PM07 Appendix A (cubic spline, in units G = m = h = 1): potential, force and dphi/dh.
TEST(CubicSplineSoftening, MatchesPriceMonaghanAppendixA) {
  using S = KernelSoftening<CubicSpline<3>>;
  for (int i = 0; i <= 400; ++i) {
    const Real q = 2.4 * i / 400 + 1e-3, q2 = q * q, q3 = q2 * q, q4 = q3 * q, q5 = q4 * q;
    Real phi, force, dphidh;
    if (q < 1) {
      phi = 2.0 / 3 * q2 - 0.3 * q4 + 0.1 * q5 - 1.4;
      force = 4.0 / 3 * q - 1.2 * q3 + 0.5 * q4;
      dphidh = 1.4 - 2 * q2 + 1.5 * q4 - 0.6 * q5;
    } else if (q < 2) {
      phi = 4.0 / 3 * q2 - q3 + 0.3 * q4 - 1.0 / 30 * q5 - 1.6 + 1.0 / (15 * q);
      force = 8.0 / 3 * q - 3 * q2 + 1.2 * q3 - 1.0 / 6 * q4 - 1.0 / (15 * q2);
      dphidh = 1.6 - 4 * q2 + 4 * q3 - 1.5 * q4 + 0.2 * q5;
    } else {
      phi = -1 / q, force = 1 / q2, dphidh = 0;
    }
    EXPECT_NEAR(S::phi(q, 1), phi, 1e-14) << q;
    EXPECT_NEAR(S::dphi_dr(q, 1), force, 1e-14) << q;
    EXPECT_NEAR(S::dphi_dh(q, 1), dphidh, 1e-14) << q;
  }
}
