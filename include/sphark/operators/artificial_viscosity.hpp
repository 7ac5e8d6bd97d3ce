#pragma once
// Monaghan (1992) artificial viscosity, the textbook choice for weakly compressible SPH:
//   Pi_ab = -alpha c_ab mu_ab / rho_ab,  mu_ab = h v_ab.x_ab / (r_ab^2 + eps h^2)  (v_ab.x_ab < 0)
//   dv_a/dt += - sum_b m_b Pi_ab grad_a W_ab
// It acts only on approaching pairs, conserves momentum exactly (Pi_ab = Pi_ba) and in the
// continuum limit equals a shear viscosity nu = alpha h c / (2 (D + 2)) (Monaghan 2005, eq. 4.9).
// Branch-free (for lanes of pairs, simd/lanes.hpp): a receding pair has min(v_ab.x_ab, 0) = 0.
#include <type_traits>

#include "sphark/core/types.hpp"
#include "sphark/simd/lanes.hpp"

namespace sphark {

template <int D, class S, class V>
inline V monaghan_viscosity_term(S m_b, std::type_identity_t<S> alpha, std::type_identity_t<S> c_ab,
                                 std::type_identity_t<S> rho_ab, std::type_identity_t<S> h,
                                 const std::type_identity_t<V>& x_ab, const std::type_identity_t<V>& v_ab,
                                 const V& grad_w) {
  const S vr = simd::min(v_ab.dot(x_ab), S{});  // approaching pairs only
  const S mu = h * vr / (x_ab.squaredNorm() + 0.01 * h * h);
  const S pi_ab = -alpha * c_ab * mu / rho_ab;
  return -m_b * pi_ab * grad_w;
}

}  // namespace sphark
