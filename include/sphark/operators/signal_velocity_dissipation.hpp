#pragma once
// Artificial dissipation in the signal-velocity form (Monaghan 1997; Price 2008), the pair terms
// of the SPMHD scheme. All use the mean kernel gradient gbar = (grad_a W_ab(h_a) + grad_a W_ab(h_b))/2
// through rhat_dot_gbar = rhat_ab . gbar (< 0; rhat_ab = x_ab / r_ab), and the mean density
// rho_ab = (rho_a + rho_b)/2 through inv_rho_ab = 1/rho_ab. Every term is antisymmetric (momentum)
// or symmetric (heating) under a <-> b, so momentum and total energy are conserved exactly.
// Real scalars and Eigen vectors, or lanes of pairs (simd/lanes.hpp).
#include <cmath>
#include <type_traits>

#include "sphark/core/types.hpp"
#include "sphark/simd/lanes.hpp"

namespace sphark {

// Pair closing speed w_ab = v_ab . rhat_ab; viscosity acts on approaching pairs only (w_ab < 0).
// (For lanes: a mask, one flag per lane.)
template <class S>
inline auto approaching(S w_ab) { return w_ab < 0; }

template <int D, class S = Real, class V = Vec<D>>
struct ViscousPairTerm {
  V dv_dt;  // summand of dv_a/dt
  S du_dt;  // summand of du_a/dt (the matching heating, >= 0)
};

// Monaghan (1997) viscosity for an approaching pair (w_ab < 0):
//   Pi_ab = -alpha v_sig w_ab / rho_ab,  v_sig = (c_a + c_b)/2 - beta w_ab,
//   dv_a/dt += -m_b Pi_ab gbar,  du_a/dt += m_b Pi_ab / 2 v_ab . gbar  (v_ab . gbar = w_ab rhat . gbar).
template <int D, class V, class S = simd::scalar_of<V>>
inline ViscousPairTerm<D, S, V> signal_velocity_viscosity_term(std::type_identity_t<S> m_b, std::type_identity_t<S> alpha,
                                                               std::type_identity_t<S> beta, std::type_identity_t<S> c_a,
                                                               std::type_identity_t<S> c_b, std::type_identity_t<S> w_ab,
                                                               std::type_identity_t<S> inv_rho_ab, const V& rhat,
                                                               std::type_identity_t<S> rhat_dot_gbar) {
  const S v_sig = 0.5 * (c_a + c_b) - beta * w_ab;
  const S pi_ab = -alpha * v_sig * w_ab * inv_rho_ab;
  return {-((m_b * pi_ab * rhat_dot_gbar) * rhat), 0.5 * m_b * pi_ab * w_ab * rhat_dot_gbar};
}

// Price (2008) artificial thermal conductivity, v_sig^u = sqrt(|P_a - P_b| / rho_ab):
//   du_a/dt += m_b alpha_u v_sig^u (u_a - u_b) / rho_ab  rhat . gbar.
template <class S>
inline S conductivity_term(S m_b, std::type_identity_t<S> alpha_u, std::type_identity_t<S> P_a,
                           std::type_identity_t<S> P_b, std::type_identity_t<S> u_a, std::type_identity_t<S> u_b,
                           std::type_identity_t<S> inv_rho_ab, std::type_identity_t<S> rhat_dot_gbar) {
  const S v_sig_u = simd::sqrt(simd::abs(P_a - P_b) * inv_rho_ab);
  return m_b * alpha_u * v_sig_u * (u_a - u_b) * inv_rho_ab * rhat_dot_gbar;
}

}  // namespace sphark
