#pragma once
// The conjugate operator pair of constrained divergence cleaning (seed 000, §II-C and §III-C).
// For a vector field A (B for SPMHD, v for weakly compressible SPH) and the cleaning scalar psi:
//
//   difference divergence   div A_a = -1/(Omega_a rho_a) sum_b m_b (A_a - A_b) . grad_a W_ab(h_a)
//                                                           seed 000, eq. (20) (B) and eq. (36) (v)
//   symmetric gradient      grad psi_a / rho_a = sum_b m_b ( psi_a/(Omega_a rho_a^2) grad_a W_ab(h_a)
//                                                          + psi_b/(Omega_b rho_b^2) grad_a W_ab(h_b) )
//                                                           seed 000, eq. (23) (B) and eq. (39) (v)
//   difference gradient     grad f_a = 1/(Omega_a rho_a) sum_b m_b (f_b - f_a) grad_a W_ab(h_a)
//                           (NOT the conjugate of the divergence: the previous, non-conservative
//                           choice for grad psi, seed 000 §I; also grad alpha of Euler potentials)
//
// These are adjoint to each other under the energy inner products of eqs. (21)/(37), which is why
// the cleaning subsystem conserves energy exactly when both are used together. The pair terms
// below are the summands; callers accumulate them over the neighbour list. Gradients may be
// vectors or RadialGradient (pair_geometry.hpp), scalars Real or lanes of pairs (simd/lanes.hpp,
// with LaneVec gradients): the formula is the same, written once.
#include <type_traits>

#include "sphark/core/types.hpp"

namespace sphark {

// Summand of the difference divergence: m_b (A_a - A_b) . grad_a W_ab(h_a).
// div A_a = -(1 / (Omega_a rho_a)) * sum of these.
template <class S, class VA, class VB, class G>
inline S difference_divergence_term(S m_b, const VA& A_a, const VB& A_b, const G& grad_w_a) {
  return m_b * (A_a - A_b).dot(grad_w_a);
}

// Summand of the symmetric gradient (per unit density):
// m_b ( q_a grad_a W_ab(h_a) + q_b grad_a W_ab(h_b) ),  q = psi / (Omega rho^2).
// grad psi_a / rho_a = sum of these.
template <class S, class G>
inline G symmetric_gradient_term(S m_b, std::type_identity_t<S> q_a, const G& grad_w_a, std::type_identity_t<S> q_b,
                                 const G& grad_w_b) {
  return m_b * (q_a * grad_w_a + q_b * grad_w_b);
}
// Summand of the difference gradient: m_b (f_b - f_a) grad_a W_ab(h_a).
// grad f_a = (1 / (Omega_a rho_a)) * sum of these.
template <class S, class G>
inline G difference_gradient_term(S m_b, std::type_identity_t<S> f_a, std::type_identity_t<S> f_b, const G& grad_w_a) {
  return m_b * (f_b - f_a) * grad_w_a;
}

}  // namespace sphark
