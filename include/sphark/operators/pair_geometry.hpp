#pragma once
// What every pair operator needs about a pair (a, b): separation, distance, kernel gradient.
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

}  // namespace sphark
