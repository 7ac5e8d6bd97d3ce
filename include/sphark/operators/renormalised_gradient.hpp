#pragma once
// Renormalised (first-order consistent) SPH gradient, Randles & Libersky (1996); the form used
// by delta-SPH (Antuono et al. 2010, eq. (12)):
//   <grad f>^L_a = L_a sum_b (f_b - f_a) grad_a W_ab V_b,   L_a = [ sum_b x_ba (x) grad_a W_ab V_b ]^-1
// exact for every linear field f. Callers accumulate the two sums with the terms below and call
// finish(); a singular matrix (a particle with too few neighbours) falls back to L = I.
#include <Eigen/Dense>

#include "sphark/core/types.hpp"

namespace sphark {

template <int D>
struct RenormalisedGradient {
  Eigen::Matrix<Real, D, D> moment = Eigen::Matrix<Real, D, D>::Zero();  // sum_b x_ba (x) grad_a W_ab V_b
  Vec<D> raw = Vec<D>::Zero();                                            // sum_b (f_b - f_a) grad_a W_ab V_b

  void add(Real volume_b, Real f_a, Real f_b, const Vec<D>& x_ab, const Vec<D>& grad_w) {
    moment -= volume_b * x_ab * grad_w.transpose();  // x_ba = -x_ab
    raw += volume_b * (f_b - f_a) * grad_w;
  }

  Vec<D> finish() const {
    const Real det = moment.determinant();
    if (std::abs(det) < 1e-3 * std::pow(moment.trace() / D, D) || !std::isfinite(det)) return raw;
    // moment approximates the identity; the gradient is L^T applied as in Randles & Libersky:
    // sum_b (f_b - f_a) grad W V_b ~ moment^T grad f  =>  grad f = moment^-T raw
    return moment.transpose().partialPivLu().solve(raw);
  }
};

}  // namespace sphark
