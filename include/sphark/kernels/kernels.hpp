#pragma once
// Smoothing kernels W(r, h) = sigma_D / h^D * f(q), q = r / h, with compact support q < Q.
// Every kernel is exactly normalised: integral of W over R^D equals 1 (tests/kernels).
//
//   cubic spline (M4)      Q = 2    Monaghan (2005), Rep. Prog. Phys. 68, eq. (2.6)
//   quintic spline (M6)    Q = 3    Morris et al. (1997)
//   Wendland C2, C4, C6    Q = 2    Wendland (1995); Dehnen & Aly (2012), Table 1 with H = 2h
//
// A kernel type K provides, for dimension D:
//   K::support            Q, the support radius in units of h
//   K::w(r, h)            W
//   K::dw_dr(r, h)        dW/dr   (the gradient is  grad_a W_ab = dw_dr * (x_a - x_b) / r)
//   K::f_over_r(r, h)     (dW/dr) / r, finite at r = 0 (what pair loops use)
//   K::name               the name used on the command line
// and, for the pair loops' lanes (S = Real or a lane type of simd/lanes.hpp), branch-free forms
// at unit smoothing length, zero beyond the support (W(r, h) = unit_w(r/h) / h^D, etc.):
//   K::unit_w(q)                  sigma_D f(q)
//   K::unit_q_dw(q)               sigma_D q f'(q)
//   K::unit_f_over_r(q, inv_q)    sigma_D f'(q) / q   (inv_q = 1/q; only the splines use it)
// They equal the forms above to round-off (tests/unit/kernels_test.cpp).
#include <cmath>
#include <string_view>

#include "sphark/core/types.hpp"
#include "sphark/simd/lanes.hpp"

namespace sphark {

namespace kernel_detail {
inline constexpr Real ipow(Real x, int n) {
  Real r = 1;
  for (int i = 0; i < n; ++i) r *= x;
  return r;
}
}  // namespace kernel_detail

// Shape function f(q) with its derivative f'(q) and its reduced derivative f'(q)/q
// (well defined at q = 0 for every kernel below), plus the normalisation sigma_D.
template <int D, class Shape>
struct RadialKernel {
  static constexpr Real support = Shape::support;
  static constexpr std::string_view name = Shape::name;
  static constexpr Real norm(Real h) { return Shape::template sigma<D>() / kernel_detail::ipow(h, D); }
  static Real w(Real r, Real h) { return norm(h) * Shape::f(r / h); }
  static Real dw_dr(Real r, Real h) { return norm(h) / h * Shape::df(r / h); }
  static Real f_over_r(Real r, Real h) { return f_over_r_scaled(r, h, f_over_r_scale(h)); }
  // f_over_r in two factors, the first a particle's own (a loop over its neighbours computes it
  // once): f_over_r(r, h) = f_over_r_scaled(r, h, f_over_r_scale(h)), bit for bit.
  static Real f_over_r_scale(Real h) { return norm(h) / (h * h); }
  static Real f_over_r_scaled(Real r, Real h, Real scale) { return scale * Shape::df_over_q(r / h); }

  template <class S>
  static S unit_w(S q) { return Shape::template sigma<D>() * Shape::f_lanes(q); }
  template <class S>
  static S unit_q_dw(S q) { return Shape::template sigma<D>() * Shape::q_df_lanes(q); }
  template <class S>
  static S unit_f_over_r(S q, S inv_q) { return Shape::template sigma<D>() * Shape::df_over_q_lanes(q, inv_q); }
};

struct CubicSplineShape {
  static constexpr Real support = 2;
  static constexpr std::string_view name = "cubic";
  template <int D>
  static constexpr Real sigma() {
    return D == 1 ? 2.0 / 3.0 : D == 2 ? 10.0 / (7.0 * kPi) : 1.0 / kPi;
  }
  static Real f(Real q) {
    if (q < 1) return 1 - 1.5 * q * q + 0.75 * q * q * q;
    if (q < 2) return 0.25 * kernel_detail::ipow(2 - q, 3);
    return 0;
  }
  static Real df_over_q(Real q) {
    if (q < 1) return -3 + 2.25 * q;
    if (q < 2) return -0.75 * (2 - q) * (2 - q) / q;
    return 0;
  }
  static Real df(Real q) { return q < 1 ? q * df_over_q(q) : (q < 2 ? -0.75 * (2 - q) * (2 - q) : 0); }
  // branch-free, a = max(2 - q, 0), b = max(1 - q, 0): f = a^3/4 - b^3, f' = 3 b^2 - 3 a^2 / 4
  template <class S>
  static S f_lanes(S q) {
    const S a = simd::positive_part(2 - q), b = simd::positive_part(1 - q);
    return 0.25 * a * a * a - b * b * b;
  }
  template <class S>
  static S q_df_lanes(S q) {
    const S a = simd::positive_part(2 - q), b = simd::positive_part(1 - q);
    return q * (3 * b * b - 0.75 * a * a);
  }
  template <class S>
  static S df_over_q_lanes(S q, S inv_q) {  // the inner form without the division by q
    const S a = simd::positive_part(2 - q);
    return q < 1 ? -3 + 2.25 * q : -0.75 * a * a * inv_q;
  }
};

struct QuinticSplineShape {
  static constexpr Real support = 3;
  static constexpr std::string_view name = "quintic";
  template <int D>
  static constexpr Real sigma() {
    return D == 1 ? 1.0 / 120.0 : D == 2 ? 7.0 / (478.0 * kPi) : 1.0 / (120.0 * kPi);
  }
  static Real f(Real q) {
    using kernel_detail::ipow;
    Real s = 0;
    if (q < 3) s += ipow(3 - q, 5);
    if (q < 2) s -= 6 * ipow(2 - q, 5);
    if (q < 1) s += 15 * ipow(1 - q, 5);
    return s;
  }
  static Real df(Real q) {
    using kernel_detail::ipow;
    Real s = 0;
    if (q < 3) s -= 5 * ipow(3 - q, 4);
    if (q < 2) s += 30 * ipow(2 - q, 4);
    if (q < 1) s -= 75 * ipow(1 - q, 4);
    return s;
  }
  // df/q near q = 0: df(q) = -120 q + O(q^3) for the M6 spline, so the limit is -120.
  static Real df_over_q(Real q) { return q > 1e-12 ? df(q) / q : -120.0; }
  // branch-free, a = max(3 - q, 0), b = max(2 - q, 0), c = max(1 - q, 0)
  template <class S>
  static S f_lanes(S q) {
    const S a = simd::positive_part(3 - q), b = simd::positive_part(2 - q), c = simd::positive_part(1 - q);
    const S a2 = a * a, b2 = b * b, c2 = c * c;
    return a2 * a2 * a - 6 * (b2 * b2 * b) + 15 * (c2 * c2 * c);
  }
  template <class S>
  static S df_lanes(S q) {
    const S a = simd::positive_part(3 - q), b = simd::positive_part(2 - q), c = simd::positive_part(1 - q);
    const S a2 = a * a, b2 = b * b, c2 = c * c;
    return -5 * (a2 * a2) + 30 * (b2 * b2) - 75 * (c2 * c2);
  }
  template <class S>
  static S q_df_lanes(S q) { return q * df_lanes(q); }
  template <class S>
  static S df_over_q_lanes(S q, S inv_q) { return q > 1e-12 ? df_lanes(q) * inv_q : simd::broadcast<S>(-120.0); }
};

// Wendland functions with support H = 2h, written in t = q / 2 in [0, 1).
struct WendlandC2Shape {
  static constexpr Real support = 2;
  static constexpr std::string_view name = "wendland_c2";
  // 1D: psi_{3,1} = (1-t)^3 (1 + 3t); 2D/3D: psi_{3,1} = (1-t)^4 (1 + 4t).
  template <int D>
  static constexpr Real sigma() {
    return D == 1 ? 5.0 / 8.0 : D == 2 ? 7.0 / (4.0 * kPi) : 21.0 / (16.0 * kPi);
  }
  template <int D>
  static Real f_d(Real q) {
    const Real t = 0.5 * q;
    if (t >= 1) return 0;
    using kernel_detail::ipow;
    return D == 1 ? ipow(1 - t, 3) * (1 + 3 * t) : ipow(1 - t, 4) * (1 + 4 * t);
  }
  // d/dq of the above:  1D: -6 t (1-t)^2 * 1/2 * 2 -> -6 t (1-t)^2 / ... (see df_over_q_d)
  template <int D>
  static Real df_over_q_d(Real q) {
    const Real t = 0.5 * q;
    if (t >= 1) return 0;
    using kernel_detail::ipow;
    // 1D: d/dt = -12 t (1-t)^2 ;  2D/3D: d/dt = -20 t (1-t)^3 ;  d/dq = d/dt / 2 ;  / q = / (2t)
    return D == 1 ? -3.0 * ipow(1 - t, 2) : -5.0 * ipow(1 - t, 3);
  }
  // branch-free, s = max(1 - t, 0)
  template <int D, class S>
  static S f_lanes_d(S q) {
    const S t = 0.5 * q, s = simd::positive_part(1 - t), s2 = s * s;
    return D == 1 ? s2 * s * (1 + 3 * t) : s2 * s2 * (1 + 4 * t);
  }
  template <int D, class S>
  static S df_over_q_lanes_d(S q) {
    const S s = simd::positive_part(1 - 0.5 * q);
    return D == 1 ? -3.0 * (s * s) : -5.0 * (s * s * s);
  }
};

struct WendlandC4Shape {
  static constexpr Real support = 2;
  static constexpr std::string_view name = "wendland_c4";
  // 1D: psi_{4,2} = (1-t)^5 (1 + 5t + 8t^2); 2D/3D: psi_{5,2} = (1-t)^6 (1 + 6t + 35/3 t^2).
  template <int D>
  static constexpr Real sigma() {
    return D == 1 ? 3.0 / 4.0 : D == 2 ? 9.0 / (4.0 * kPi) : 495.0 / (256.0 * kPi);
  }
  template <int D>
  static Real f_d(Real q) {
    const Real t = 0.5 * q;
    if (t >= 1) return 0;
    using kernel_detail::ipow;
    return D == 1 ? ipow(1 - t, 5) * (1 + 5 * t + 8 * t * t)
                  : ipow(1 - t, 6) * (1 + 6 * t + 35.0 / 3.0 * t * t);
  }
  template <int D>
  static Real df_over_q_d(Real q) {
    const Real t = 0.5 * q;
    if (t >= 1) return 0;
    using kernel_detail::ipow;
    // 1D: d/dt = -14 t (1-t)^4 (1 + 4t);  2D/3D: d/dt = -56/3 t (1-t)^5 (1 + 5t)
    return D == 1 ? -3.5 * ipow(1 - t, 4) * (1 + 4 * t) : -14.0 / 3.0 * ipow(1 - t, 5) * (1 + 5 * t);
  }
  template <int D, class S>
  static S f_lanes_d(S q) {
    const S t = 0.5 * q, s = simd::positive_part(1 - t), s2 = s * s, s4 = s2 * s2;
    return D == 1 ? s4 * s * (1 + 5 * t + 8 * t * t) : s4 * s2 * (1 + 6 * t + 35.0 / 3.0 * t * t);
  }
  template <int D, class S>
  static S df_over_q_lanes_d(S q) {
    const S t = 0.5 * q, s = simd::positive_part(1 - t), s2 = s * s, s4 = s2 * s2;
    return D == 1 ? -3.5 * s4 * (1 + 4 * t) : -14.0 / 3.0 * (s4 * s) * (1 + 5 * t);
  }
};

struct WendlandC6Shape {
  static constexpr Real support = 2;
  static constexpr std::string_view name = "wendland_c6";
  // 1D: psi_{5,3} = (1-t)^7 (1 + 7t + 19t^2 + 21t^3); 2D/3D: psi_{6,3} = (1-t)^8 (1 + 8t + 25t^2 + 32t^3).
  template <int D>
  static constexpr Real sigma() {
    return D == 1 ? 55.0 / 64.0 : D == 2 ? 39.0 / (14.0 * kPi) : 1365.0 / (512.0 * kPi);
  }
  template <int D>
  static Real f_d(Real q) {
    const Real t = 0.5 * q;
    if (t >= 1) return 0;
    using kernel_detail::ipow;
    return D == 1 ? ipow(1 - t, 7) * (1 + 7 * t + 19 * t * t + 21 * t * t * t)
                  : ipow(1 - t, 8) * (1 + 8 * t + 25 * t * t + 32 * t * t * t);
  }
  template <int D>
  static Real df_over_q_d(Real q) {
    const Real t = 0.5 * q;
    if (t >= 1) return 0;
    using kernel_detail::ipow;
    // 1D: d/dt = -6 t (1-t)^6 (3 + 18t + 35t^2);  2D/3D: d/dt = -22 t (1-t)^7 (1 + 7t + 16t^2)
    return D == 1 ? -1.5 * ipow(1 - t, 6) * (3 + 18 * t + 35 * t * t)
                  : -5.5 * ipow(1 - t, 7) * (1 + 7 * t + 16 * t * t);
  }
  template <int D, class S>
  static S f_lanes_d(S q) {
    const S t = 0.5 * q, s = simd::positive_part(1 - t), s2 = s * s, s4 = s2 * s2;
    return D == 1 ? s4 * s2 * s * (1 + 7 * t + 19 * t * t + 21 * t * t * t)
                  : s4 * s4 * (1 + 8 * t + 25 * t * t + 32 * t * t * t);
  }
  template <int D, class S>
  static S df_over_q_lanes_d(S q) {
    const S t = 0.5 * q, s = simd::positive_part(1 - t), s2 = s * s, s4 = s2 * s2;
    return D == 1 ? -1.5 * (s4 * s2) * (3 + 18 * t + 35 * t * t) : -5.5 * (s4 * s2 * s) * (1 + 7 * t + 16 * t * t);
  }
};

// Wendland shapes depend on D; bind D so that RadialKernel sees f, df, df_over_q.
template <int D, class W>
struct WendlandBound {
  static constexpr Real support = W::support;
  static constexpr std::string_view name = W::name;
  template <int DD>
  static constexpr Real sigma() { return W::template sigma<DD>(); }
  static Real f(Real q) { return W::template f_d<D>(q); }
  static Real df_over_q(Real q) { return W::template df_over_q_d<D>(q); }
  static Real df(Real q) { return q * df_over_q(q); }
  template <class S>
  static S f_lanes(S q) { return W::template f_lanes_d<D>(q); }
  template <class S>
  static S q_df_lanes(S q) { return q * q * W::template df_over_q_lanes_d<D>(q); }
  template <class S>
  static S df_over_q_lanes(S q, S /*inv_q*/) { return W::template df_over_q_lanes_d<D>(q); }
};

template <int D> using CubicSpline = RadialKernel<D, CubicSplineShape>;
template <int D> using QuinticSpline = RadialKernel<D, QuinticSplineShape>;
template <int D> using WendlandC2 = RadialKernel<D, WendlandBound<D, WendlandC2Shape>>;
template <int D> using WendlandC4 = RadialKernel<D, WendlandBound<D, WendlandC4Shape>>;
template <int D> using WendlandC6 = RadialKernel<D, WendlandBound<D, WendlandC6Shape>>;

}  // namespace sphark
