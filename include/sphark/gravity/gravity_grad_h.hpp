#pragma once
// The gravitational grad-h term of adaptive kernel softening (Price & Monaghan 2007, MNRAS 374,
// 1347, §3; "PM07"), as small pieces an SPH neighbour loop calls.
//
// With the gravitational energy (self terms b = a included, as Phantom does)
//   E_g = (G/2) sum_a sum_b m_a m_b phi_ab,   phi_ab = (phi(r_ab, h_a) + phi(r_ab, h_b)) / 2,
// and h_a = h(rho_a) from the density summation, -dE_g/dx_a gives the softened pair force plus
//   a_a += -(G/2) sum_b m_b [ zeta_a/Omega_a grad_a W_ab(h_a) + zeta_b/Omega_b grad_a W_ab(h_b) ]
//   zeta_a = (dh_a/drho_a) sum_b m_b dphi(r_ab, h_a)/dh_a       (b = a included)
// with Omega_a = 1 - (dh_a/drho_a) sum_b m_b dW_ab(h_a)/dh_a (seed 000, eq. (4)-(5); Price 2012,
// eq. 29) and dh/drho = -h / (3 rho) for h = eta (m / rho)^(1/3). The self term in zeta is there
// because E_g contains (G/2) m_a^2 phi(0, h_a) (the self energy in the tree/direct potentials).
// tests/gravity/grad_h_test.cpp checks m_a a_a = -dE_g/dx_a by finite differences.
//
// Use in a density loop:   s = zeta_init<K>(m_a, h_a);  s += zeta_pair<K>(m_b, r_ab, h_a) ...;
//                          zeta_a = zeta_finish(s, h_a, rho_a);
// and in the force loop:   a_a += grad_h_gravity_pair<K>(G, m_b, x_a - x_b, r_ab, h_a, h_b,
//                                                       zeta_a / Omega_a, zeta_b / Omega_b).
// (The SPMHD scheme adds the same term as an isotropic stress -(G/2) zeta/Omega in its pair
// loop: src/schemes/spmhd/spmhd_forces.cpp, pair_loop_arrays.)
#include "sphark/core/types.hpp"
#include "sphark/gravity/kernel_softening.hpp"

namespace sphark {

// The b = a term of the zeta sum: m_a dphi(0, h_a)/dh_a.
template <class K>
inline Real zeta_init(Real m_a, Real h_a) {
  return m_a * KernelSoftening<K>::dphi_dh(0, h_a);
}

// One neighbour b (r_ab < support * h_a; zero beyond): m_b dphi(r_ab, h_a)/dh_a.
template <class K>
inline Real zeta_pair(Real m_b, Real r_ab, Real h_a) {
  return m_b * KernelSoftening<K>::dphi_dh(r_ab, h_a);
}

// zeta_a = (dh_a/drho_a) * sum, with dh/drho = -h / (3 rho) (h = eta (m/rho)^(1/3)).
inline Real zeta_finish(Real sum, Real h_a, Real rho_a) { return -h_a / (3 * rho_a) * sum; }

// The grad-h acceleration of a due to b (x_ab = x_a - x_b, r_ab = |x_ab|), PM07 §3:
// -(G/2) m_b [zeta_a/Omega_a dW/dr(h_a) + zeta_b/Omega_b dW/dr(h_b)] x_ab / r_ab.
// The pair (a, b) and (b, a) terms are m_b f x_ab and m_a f x_ba with the same f: momentum is
// conserved. zo_a = zeta_a / Omega_a.
template <class K>
inline Vec<3> grad_h_gravity_pair(Real G, Real m_b, const Vec<3>& x_ab, Real r_ab, Real h_a, Real h_b, Real zo_a,
                                  Real zo_b) {
  const Real f = zo_a * K::f_over_r(r_ab, h_a) + zo_b * K::f_over_r(r_ab, h_b);
  return (-0.5 * G * m_b * f) * x_ab;
}

}  // namespace sphark
