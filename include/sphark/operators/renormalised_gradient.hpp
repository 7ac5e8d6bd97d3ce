#pragma once
// Renormalised (first-order consistent) SPH gradient, Randles & Libersky (1996); the form used
// by delta-SPH (Antuono et al. 2010, eq. (12)):
//   <grad f>^L_a = L_a sum_b (f_b - f_a) grad_a W_ab V_b,   L_a = [ sum_b x_ba (x) grad_a W_ab V_b ]^-1
// exact for every linear field f. Callers accumulate the two sums with the terms below and call
// finish(); a singular matrix (a particle with too few neighbours) falls back to L = I.
#include <Eigen/Dense>

#include <type_traits>

#include "sphark/core/types.hpp"
#include "sphark/simd/lanes.hpp"

namespace sphark {

// S = Real, or a lane type (simd/lanes.hpp) for lanes of pairs: then summed() adds the lanes.
template <int D, class S = Real>
struct RenormalisedGradient {
  S moment[D][D] = {};  // sum_b x_ba (x) grad_a W_ab V_b
  S raw[D] = {};        // sum_b (f_b - f_a) grad_a W_ab V_b

  template <class V>
  void add(S volume_b, S f_a, S f_b, const V& x_ab, const std::type_identity_t<V>& grad_w) {
    for (int i = 0; i < D; ++i) {
      for (int j = 0; j < D; ++j) moment[i][j] -= volume_b * x_ab[i] * grad_w[j];  // x_ba = -x_ab
      raw[i] += volume_b * (f_b - f_a) * grad_w[i];
    }
  }

  RenormalisedGradient<D> summed() const {
    RenormalisedGradient<D> g;
    for (int i = 0; i < D; ++i) {
      for (int j = 0; j < D; ++j) g.moment[i][j] = simd::sum(moment[i][j]);
      g.raw[i] = simd::sum(raw[i]);
    }
    return g;
  }

  Vec<D> finish() const
    requires std::is_same_v<S, Real>
  {
    Eigen::Matrix<Real, D, D> M;
    Vec<D> r;
    for (int i = 0; i < D; ++i) {
      for (int j = 0; j < D; ++j) M(i, j) = moment[i][j];
      r[i] = raw[i];
    }
    const Real det = M.determinant();
    if (std::abs(det) < 1e-3 * std::pow(M.trace() / D, D) || !std::isfinite(det)) return r;
    // moment approximates the identity; the gradient is L^T applied as in Randles & Libersky:
    // sum_b (f_b - f_a) grad W V_b ~ moment^T grad f  =>  grad f = moment^-T raw
    return M.transpose().partialPivLu().solve(r);
  }
};

}  // namespace sphark
