#pragma once
// What every pair operator needs about a pair (a, b): separation, distance, kernel gradient.
#include <type_traits>

#include "sphark/core/types.hpp"

namespace sphark {

template <int D>
struct PairGeometry {
  Vec<D> x_ab;     // x_a - x_b (minimum image)
  Real r;          // |x_ab|
  Vec<D> grad_w;   // grad_a W_ab(h) = (dW/dr) x_ab / r
};

template <class Kernel, int D>
inline PairGeometry<D> pair_geometry(const Vec<D>& x_ab, Real h) {
  const Real r = x_ab.norm();
  return {x_ab, r, Kernel::f_over_r(r, h) * x_ab};
}

// A kernel gradient grad_a W_ab(h) = F x_ab with F = (dW/dr)/r, kept as the factor F and the
// pair separation x_ab. Scaling and adding gradients of ONE pair (grad_a W_ab(h_a) and
// grad_a W_ab(h_b) share x_ab) stays in this form, so that an operator written once for vectors,
// e.g. m (q_a grad_a W_ab(h_a) + q_b grad_a W_ab(h_b)), computes (m (q_a F_a + q_b F_b)) x_ab:
// the scalars are combined first, then one product with x_ab (fewer operations, other rounding
// than with the gradients as vectors).
// (x_ab is referred to, not copied: a RadialGradient lives as long as the pair's x_ab.)
// (S, V: Real and Vec<D>, or lanes of pairs, simd/lanes.hpp.)
template <int D, class S = Real, class V = Vec<D>>
struct RadialGradient {
  S factor;
  const V& x_ab;
  V vector() const { return factor * x_ab; }
};

template <int D, class S, class V>
inline RadialGradient<D, S, V> operator*(std::type_identity_t<S> s, const RadialGradient<D, S, V>& g) {
  return {s * g.factor, g.x_ab};
}

// Both gradients must belong to the same pair (same x_ab).
template <int D, class S, class V>
inline RadialGradient<D, S, V> operator+(const RadialGradient<D, S, V>& g1, const RadialGradient<D, S, V>& g2) {
  return {g1.factor + g2.factor, g1.x_ab};
}

}  // namespace sphark
