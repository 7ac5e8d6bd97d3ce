#pragma once
// Kernel values at unit smoothing length for the SPMHD pair loops: W(r, h) = w1(q) / h^D and
// (dW/dr)/r = f1(q) / h^(D+2) with q = r / h, w1 = K::w(q, 1), f1 = K::f_over_r(q, 1).
// The generic form calls K; the cubic spline (Monaghan 2005, eq. (2.6)) has a branch-free form
// with a = max(2 - q, 0), b = max(1 - q, 0):  f = a^3/4 - b^3,  df/dq = 3b^2 - 3a^2/4.
// Both agree with kernels.hpp to round-off (tests/kernels covers the kernels themselves).
#include <algorithm>

#include "sphark/kernels/kernels.hpp"

namespace sphark {

template <class K>
struct UnitKernel {
  // w1(q) and q^2 f1(q) (the density sum and its h-derivative, seed 000 eqs. (4)-(5)).
  static void w_and_q2f(Real q, Real& w1, Real& q2f1) {
    w1 = K::w(q, 1.0);
    q2f1 = q * q * K::f_over_r(q, 1.0);
  }
  // f1(q), given also 1/q (unused here).
  static Real f_over_r(Real q, Real /*inv_q*/) { return K::f_over_r(q, 1.0); }
};

template <int D>
struct UnitKernel<CubicSpline<D>> {
  static constexpr Real sigma = CubicSplineShape::sigma<D>();
  static void w_and_q2f(Real q, Real& w1, Real& q2f1) {
    const Real a = std::max(2 - q, 0.0), b = std::max(1 - q, 0.0);
    w1 = sigma * (0.25 * a * a * a - b * b * b);
    q2f1 = sigma * q * (3 * b * b - 0.75 * a * a);  // q * df/dq
  }
  static Real f_over_r(Real q, Real inv_q) {
    const Real a = std::max(2 - q, 0.0), b = std::max(1 - q, 0.0);
    return sigma * (3 * b * b - 0.75 * a * a) * inv_q;  // (df/dq) / q
  }
};

}  // namespace sphark
