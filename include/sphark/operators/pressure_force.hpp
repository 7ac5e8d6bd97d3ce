#pragma once
// Symmetric SPH pressure force and continuity equation for constant h.
#include "sphark/core/types.hpp"

namespace sphark {

// seed 000, eq. (27): dv_a/dt = - sum_b m_b (P_a/rho_a^2 + P_b/rho_b^2) grad_a W_ab ; this is the summand.
template <int D>
inline Vec<D> pressure_acceleration_term(Real m_b, Real p_over_rho2_a, Real p_over_rho2_b, const Vec<D>& grad_w) {
  return -m_b * (p_over_rho2_a + p_over_rho2_b) * grad_w;
}

// seed 000, eq. (28) with the sign fixed by eq. (36): drho_a/dt = -rho_a div v_a
//   = + sum_b m_b (v_a - v_b) . grad_a W_ab.  (The printed (28) carries a spurious minus sign.)
template <int D>
inline Real continuity_term(Real m_b, const Vec<D>& v_ab, const Vec<D>& grad_w) {
  return m_b * v_ab.dot(grad_w);
}

}  // namespace sphark
