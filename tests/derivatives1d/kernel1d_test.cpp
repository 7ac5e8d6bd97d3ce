// seed 001 §II: the quintic Wendland kernel in 1D and its derivative.
#include <gtest/gtest.h>

#include <cmath>

#include "sphark/derivatives1d/kernel1d.hpp"

using sphark::Real;
using sphark::d1::SeedKernel1D;

namespace {
// The formula as printed in seed 001 §II.
Real seed_w(Real r, Real h) {
  const Real q = std::abs(r) / h, alpha = 3.0 / (128.0 * h);
  return q < 2 ? alpha * std::pow(2 - q, 5) * (2 * q * q + 2.5 * q + 1) : 0.0;
}
// seed 001 §II printed derivative (with respect to y, q = (x - y)/h); ours is minus this (d/dx).
Real seed_dw_dy(Real r, Real h) {
  const Real q = r / h, aq = std::abs(q), alpha = 3.0 / (128.0 * h);
  return aq < 2 ? 7 * alpha / h * q * std::pow(2 - aq, 4) * (2 * aq + 1) : 0.0;
}
}  // namespace

TEST(SeedKernel1D, EqualsPrintedWendlandQuintic) {
  for (Real h : {0.05, 0.3, 1.0})
    for (int k = -250; k <= 250; ++k) {
      const Real r = k * 0.01 * h;
      EXPECT_NEAR(SeedKernel1D::w(r, h), seed_w(r, h), 1e-14 * seed_w(0, h)) << "r=" << r << " h=" << h;
      // derivative with respect to x = -(derivative with respect to y)
      EXPECT_NEAR(SeedKernel1D::dw(r, h), -seed_dw_dy(r, h), 1e-13 * seed_w(0, h) / h) << "r=" << r;
    }
}

TEST(SeedKernel1D, DerivativeMatchesCentralDifference) {
  const Real h = 0.2, eps = 1e-6;
  for (int k = -39; k <= 39; ++k) {
    const Real r = k * 0.01;
    const Real fd = (SeedKernel1D::w(r + eps, h) - SeedKernel1D::w(r - eps, h)) / (2 * eps);
    EXPECT_NEAR(SeedKernel1D::dw(r, h), fd, 1e-6) << "r=" << r;
  }
}

TEST(SeedKernel1D, ContinuousMomentsInTheInterior) {
  // integral W = 1 and gamma~ = integral (y - x) W'(x - y) dy = 1 (seed 001 §III) with W' = dW/dx;
  // composite Simpson on [-2h, 2h] (the kernel is a piecewise polynomial of degree 8: error ~ 1e-12).
  const Real h = 0.1;
  const int m = 4000;
  const Real a = -2 * h, dy = 4 * h / m;
  Real w0 = 0, gt = 0, gs = 0;
  for (int k = 0; k <= m; ++k) {
    const Real s = a + k * dy, wt = (k == 0 || k == m) ? 1 : (k % 2 ? 4 : 2);  // s = y - x
    w0 += wt * SeedKernel1D::w(-s, h);
    gt += wt * s * SeedKernel1D::dw(-s, h);
    gs += wt * 0.5 * s * s * SeedKernel1D::w(-s, h);
  }
  w0 *= dy / 3;
  gt *= dy / 3;
  gs *= dy / 3;
  EXPECT_NEAR(w0, 1.0, 1e-12);
  EXPECT_NEAR(gt, 1.0, 1e-12);
  // gamma* = h^2 * integral_{-2}^{2} q^2/2 * 3/128 (2-|q|)^5 (2q^2 + 5/2|q| + 1) dq = 2 h^2 / 15,
  // the O(h^2) of seed 001 §IV.I.
  EXPECT_NEAR(gs / (h * h), 2.0 / 15.0, 1e-12);
}
