#pragma once
// Pair terms of the SPMHD operators (seed 000, §II). Each function returns the contribution of
// neighbour b to a sum over b for particle a, so that the caller's gather loop reads like the
// equation. B is always 3 components (the 2D disc test has B_z); kernel gradients g are padded
// to 3 components with zeros beyond D.
//
// Notation: g_a = grad_a W_ab(h_a), g_b = grad_a W_ab(h_b) (both along x_a - x_b), m = m_b,
// "oa" = 1 / (Omega_a rho_a^2), "ob" = 1 / (Omega_b rho_b^2).
#include <Eigen/Core>

#include "sphark/core/types.hpp"

namespace sphark::mhd {

using Vec3 = Eigen::Matrix<Real, 3, 1>;
using Mat3 = Eigen::Matrix<Real, 3, 3>;

// Maxwell stress, seed 000, eq. (8), mu0 = 1:  M = B B^T - (P + B^2/2) I.
inline Mat3 maxwell_stress(const Vec3& B, Real P) {
  return B * B.transpose() - (P + 0.5 * B.squaredNorm()) * Mat3::Identity();
}

// Momentum, seed 000, eq. (6):  m_b [ M_a/(Omega_a rho_a^2) . g_a + M_b/(Omega_b rho_b^2) . g_b ].
inline Vec3 momentum_pair(Real m, const Mat3& Ma, Real oa, const Vec3& ga, const Mat3& Mb, Real ob, const Vec3& gb) {
  return m * (oa * (Ma * ga) + ob * (Mb * gb));
}

// The B(div B) subtraction, seed 000, eq. (9): the scalar part of the sum
// m_b [ B_a/(Omega_a rho_a^2) . g_a + B_b/(Omega_b rho_b^2) . g_b ]  (multiplied by -B_a outside).
inline Real monopole_pair(Real m, const Vec3& Ba, Real oa, const Vec3& ga, const Vec3& Bb, Real ob, const Vec3& gb) {
  return m * (oa * Ba.dot(ga) + ob * Bb.dot(gb));
}

// Induction, seed 000, eq. (7): m_b [ v_ab (B_a . g_a) - B_a (v_ab . g_a) ]  (times -1/(Omega_a rho_a)).
inline Vec3 induction_pair(Real m, const Vec3& vab, const Vec3& Ba, const Vec3& ga) {
  return m * (vab * Ba.dot(ga) - Ba * vab.dot(ga));
}

// The difference divergence (20) and the symmetric gradient (23) are the generic conjugate pair
// of sphark/operators/conjugate_cleaning.hpp (difference_divergence_term, symmetric_gradient_term).

// Difference gradient (the previous, non-conservative choice for grad psi):
// m_b (psi_b - psi_a) g_a  (times 1/(Omega_a rho_a)). Not the conjugate of (20): breaks (21).
inline Vec3 difference_gradient_pair(Real m, Real psi_a, Real psi_b, const Vec3& ga) {
  return m * (psi_b - psi_a) * ga;
}

// Artificial resistivity, seed 000, eq. (10) (with rho_ab^2, as in Price & Monaghan 2005; the
// square is lost in the seed's typesetting — the printed form is not dimensionally a dB/dt):
// m_b alpha_B v_sig / rho_ab^2 (B_a - B_b) rhat . grad W  (times rho_a).
// rhat_dot_g is rhat . (g_a + g_b)/2 < 0; the matching heating is -1/2 m_b ... |B_a - B_b|^2.
inline Vec3 resistivity_pair(Real m, Real alpha_vsig, Real rho_ab, const Vec3& Bab, Real rhat_dot_g) {
  return m * alpha_vsig / (rho_ab * rho_ab) * rhat_dot_g * Bab;
}

}  // namespace sphark::mhd
