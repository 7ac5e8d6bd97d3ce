#pragma once
// Symmetric SPH pressure force and continuity equation for constant h.
// Written for Real and Vec<D>, and for lanes of pairs (simd/lanes.hpp: S a lane type, V a
// LaneVec): S and V are deduced from m_b and grad_w, the other arguments convert to them.
#include <type_traits>

#include "sphark/core/types.hpp"

namespace sphark {

// seed 000, eq. (27): dv_a/dt = - sum_b m_b (P_a/rho_a^2 + P_b/rho_b^2) grad_a W_ab ; this is the summand.
template <int D, class S, class V>
inline V pressure_acceleration_term(S m_b, std::type_identity_t<S> p_over_rho2_a, std::type_identity_t<S> p_over_rho2_b,
                                    const V& grad_w) {
  return -m_b * (p_over_rho2_a + p_over_rho2_b) * grad_w;
}

// seed 000, eq. (28) with the sign fixed by eq. (36): drho_a/dt = -rho_a div v_a
//   = + sum_b m_b (v_a - v_b) . grad_a W_ab.  (The printed (28) carries a spurious minus sign.)
template <int D, class S, class V>
inline S continuity_term(S m_b, const std::type_identity_t<V>& v_ab, const V& grad_w) {
  return m_b * v_ab.dot(grad_w);
}

}  // namespace sphark
