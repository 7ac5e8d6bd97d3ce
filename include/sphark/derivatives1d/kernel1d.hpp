#pragma once
// The kernel of seed 001 §II: the 1D Wendland function of fifth degree
//
//   W_h(r) = alpha (2 - |q|)^5 (2 q^2 + 5/2 |q| + 1),   |q| < 2,   q = r / h,   alpha = 3 / (128 h).
//
// This is exactly WendlandC4<1> of sphark/kernels/kernels.hpp:
//   3/(4h) (1 - t)^5 (1 + 5t + 8t^2),  t = q/2   ==   3/(128h) (2 - q)^5 (1 + 5q/2 + 2q^2),
// so it is reused, not rewritten (tests/derivatives1d/kernel1d_test.cpp checks the identity).
//
// Sign convention of the derivative (see docs/second_derivative_1d.md, "Corrections"):
// seed 001 prints W'_h(x - y) as the derivative with respect to y, but then states that
// gamma~(x) = integral (y - x) W'_h(x - y) dy equals 1 in the interior, which only holds for
// the derivative with respect to x. Tables 1-3 are reproduced with the x-derivative, so
//   W'_ij := dW_h/dr at r = x_i - x_j  = -7 alpha / h * q (2 - |q|)^4 (2|q| + 1).
#include <cmath>

#include "sphark/core/types.hpp"
#include "sphark/kernels/kernels.hpp"

namespace sphark::d1 {

struct SeedKernel1D {
  using Base = WendlandC4<1>;
  static constexpr Real support = Base::support;  // in units of h: W vanishes for |r| >= 2h
  // seed 001 §II, W_h(r)
  static Real w(Real r, Real h) { return Base::w(std::abs(r), h); }
  // seed 001 §II, W'_h(r) with r = x_i - x_j, derivative with respect to x_i (sign corrected)
  static Real dw(Real r, Real h) { return r * Base::f_over_r(std::abs(r), h); }
};

}  // namespace sphark::d1
