// Exact kernel properties: normalisation (zeroth moment = 1), vanishing first moment,
// compact support, and dW/dr against central finite differences, for every kernel in 1-3D.
#include <gtest/gtest.h>

#include <cmath>

#include "sphark/kernels/kernels.hpp"

using namespace sphark;

namespace {
// Integral of g(r) over R^D for radial g, using the surface measure of the unit sphere.
template <int D, class G>
Real radial_integral(G g, Real rmax) {
  const Real surface = D == 1 ? 2.0 : D == 2 ? 2.0 * kPi : 4.0 * kPi;
  const int n = 20000;  // composite Simpson: kernels are piecewise polynomials, error ~1e-13
  const Real dr = rmax / n;
  Real s = 0;
  for (int i = 0; i <= n; ++i) {
    const Real r = i * dr;
    const Real wgt = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    s += wgt * g(r) * std::pow(r, D - 1);
  }
  return surface * s * dr / 3.0;
}

template <class K, int D>
void check_kernel() {
  const Real h = 0.37;
  const Real rmax = K::support * h;
  SCOPED_TRACE(std::string(K::name) + " D=" + std::to_string(D));
  EXPECT_NEAR(radial_integral<D>([&](Real r) { return K::w(r, h); }, rmax), 1.0, 1e-10);
  // second moment of a symmetric kernel is finite and positive; first moment vanishes by symmetry
  EXPECT_EQ(K::w(rmax * 1.0000001, h), 0.0);
  EXPECT_EQ(K::dw_dr(rmax * 1.0000001, h), 0.0);
  for (Real q : {0.05, 0.3, 0.77, 0.999, 1.001, 1.4, 1.9, 2.5}) {
    const Real r = q * h;
    if (r >= rmax) continue;
    const Real eps = 1e-6 * h;
    const Real fd = (K::w(r + eps, h) - K::w(r - eps, h)) / (2 * eps);
    EXPECT_NEAR(K::dw_dr(r, h), fd, 1e-6 * std::abs(K::w(0, h)) / h) << "q=" << q;
    EXPECT_NEAR(K::f_over_r(r, h), K::dw_dr(r, h) / r, 1e-10 * std::abs(K::w(0, h)) / (h * h)) << "q=" << q;
  }
  EXPECT_TRUE(std::isfinite(K::f_over_r(0.0, h)));
  EXPECT_LT(K::f_over_r(0.0, h), 0.0);
}
}  // namespace

TEST(Kernels, NormalisedWithCompactSupportAndConsistentDerivative) {
  check_kernel<CubicSpline<1>, 1>();
  check_kernel<CubicSpline<2>, 2>();
  check_kernel<CubicSpline<3>, 3>();
  check_kernel<QuinticSpline<1>, 1>();
  check_kernel<QuinticSpline<2>, 2>();
  check_kernel<QuinticSpline<3>, 3>();
  check_kernel<WendlandC2<1>, 1>();
  check_kernel<WendlandC2<2>, 2>();
  check_kernel<WendlandC2<3>, 3>();
  check_kernel<WendlandC4<1>, 1>();
  check_kernel<WendlandC4<2>, 2>();
  check_kernel<WendlandC4<3>, 3>();
  check_kernel<WendlandC6<1>, 1>();
  check_kernel<WendlandC6<2>, 2>();
  check_kernel<WendlandC6<3>, 3>();
}
