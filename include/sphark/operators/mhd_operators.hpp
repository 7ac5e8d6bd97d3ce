#pragma once
// The SPMHD operators of seed 000, §II, in the shape of a pair loop: what each particle needs
// before the loop (init), the summand a neighbour b contributes (pair), and what closes the sum
// (finish). The SPMHD scheme (src/schemes/spmhd/spmhd_forces.cpp) calls exactly these; the
// conjugate cleaning pair (20)/(23) is shared with WCSPH (conjugate_cleaning.hpp), the artificial
// viscosity and conductivity live in signal_velocity_dissipation.hpp.
//
// Notation: g_a = grad_a W_ab(h_a), g_b = grad_a W_ab(h_b) (both along x_ab = x_a - x_b; the
// acceleration and the gradients have D components, B always 3), m_b the neighbour's mass,
// o_a = 1 / (Omega_a rho_a^2). mu0 = 1.
// The pair terms take Real scalars and Eigen vectors, or lanes of pairs (simd/lanes.hpp: lane
// scalars S, LaneVec vectors, LaneMat stresses): one formula for every width.
#include <Eigen/Core>
#include <type_traits>

#include "sphark/core/types.hpp"
#include "sphark/simd/lanes.hpp"

namespace sphark::mhd {

using Vec3 = Eigen::Matrix<Real, 3, 1>;

// init, seed 000, eq. (8) times o_a: the D x D block of M_a / (Omega_a rho_a^2),
//   M = B B^T - (P + B^2/2) I,
// written to S[D * i + j] (symmetric, so row- and column-major alike).
template <int D>
inline void maxwell_stress_over_omega_rho2(const Real* B, Real P, Real o_a, Real* S) {
  const Real p_total = P + 0.5 * (B[0] * B[0] + B[1] * B[1] + B[2] * B[2]);
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) S[D * i + j] = o_a * (B[i] * B[j] - (i == j ? p_total : 0.0));
}

// pair, seed 000, eq. (6): dv_a/dt = sum_b m_b [ S_a g_a + S_b g_b ],  S = M / (Omega rho^2).
template <class M, class SA, class SB, class G>
inline G maxwell_force_term(M m_b, const SA& S_a, const G& g_a, const SB& S_b, const G& g_b) {
  return m_b * (S_a * g_a + S_b * g_b);
}

// pair, seed 000, eq. (9) (the tensile-instability correction): the sum
//   sum_b m_b [ (o_a B_a) . g_a + (o_b B_b) . g_b ],
// the symmetric divergence of B that (6) contains; finish: dv_a/dt -= B_a * sum.
template <class M, class BA, class BB, class G>
inline M monopole_term(M m_b, const BA& oB_a, const G& g_a, const BB& oB_b, const G& g_b) {
  return m_b * (oB_a.dot(g_a) + oB_b.dot(g_b));
}
template <int D, class Acc>
inline void subtract_monopole_force(Acc& dv_dt, const Vec3& B_a, Real monopole_sum) {
  dv_dt -= B_a.template head<D>() * monopole_sum;
}

// seed 000, eq. (7): dB_a/dt = -1/(Omega_a rho_a) sum_b m_b [ v_ab (B_a . g_a) - B_a (v_ab . g_a) ].
// (The two parts are added to the sum one after the other.)
template <int D, class S = Real>
struct Induction {
  simd::VecOf<S, 3> sum = simd::VecOf<S, 3>::Zero();  // init
  template <class VD, class V3>
  void pair(S m_b, const VD& v_ab, const V3& B_a, const VD& g_a) {
    S B_dot_g = B_a[0] * g_a[0];
    for (int k = 1; k < D; ++k) B_dot_g += B_a[k] * g_a[k];
    const S v_dot_g = v_ab.dot(g_a);
    for (int k = 0; k < D; ++k) sum[k] += m_b * B_dot_g * v_ab[k];
    for (int k = 0; k < 3; ++k) sum[k] -= m_b * v_dot_g * B_a[k];
  }
  Vec3 finish(Real inv_omega_rho) const { return -inv_omega_rho * summed(); }
  Vec3 summed() const {  // the lanes added
    Vec3 s;
    for (int k = 0; k < 3; ++k) s[k] = simd::sum(sum[k]);
    return s;
  }
};

// seed 000, eq. (10), artificial resistivity, with rho_ab^2 (Price & Monaghan 2005; the square
// is lost in the seed's typesetting: the printed form is not dimensionally a dB/dt):
//   dB_a/dt = rho_a sum_b m_b alpha_B v_sig^B / rho_ab^2 (B_a - B_b) rhat . gbar,
//   du_a/dt = -1/2 sum_b m_b alpha_B v_sig^B / rho_ab^2 |B_a - B_b|^2 rhat . gbar  (heating >= 0),
// with v_sig^B = |v_ab x rhat| = |v_ab - w_ab rhat| (Price et al. 2018, Phantom; the fast speed of
// Price & Monaghan (2005) removes most of the Orszag-Tang field by t = 0.5 at 64^2 particles).
// gbar = (g_a + g_b)/2, rhat_dot_gbar = rhat . gbar < 0, w_ab = v_ab . rhat.
template <class S = Real, class V3 = Vec3>
struct ResistivePairTerm {
  V3 dB_dt;  // summand of the sum (times rho_a at finish)
  S du_dt;   // summand of du_a/dt
};
template <int D, class S, class VD, class V3>
inline ResistivePairTerm<S, V3> resistivity_term(S m_b, std::type_identity_t<S> alpha_b, const VD& v_ab,
                                                 std::type_identity_t<S> w_ab, const VD& rhat,
                                                 std::type_identity_t<S> inv_rho_ab, const V3& B_ab,
                                                 std::type_identity_t<S> rhat_dot_gbar) {
  const S v_sig_b = simd::sqrt(VD(v_ab - w_ab * rhat).squaredNorm());
  const S k = m_b * alpha_b * v_sig_b * inv_rho_ab * inv_rho_ab * rhat_dot_gbar;
  return {k * B_ab, -(0.5 * k * B_ab.squaredNorm())};
}

// finish, seed 000, eq. (19) with (25): the psi evolution
//   dpsi_a/dt = -c_h^2 (div B)_a - psi_a / tau_a - psi_a (div v)_a / 2,
//   -psi_a (div v)_a / 2 = psi_a / (2 Omega_a rho_a) sum_b m_b v_ab . g_a      (25)
// damped: with 1/tau_a = damping_rate = sigma c_h / h_a; continuity_term: with (25), where
// continuity_sum = sum_b m_b v_ab . g_a (not for fixed particles nor the non-conservative form).
// With a per-particle c_h the state is psi/c_h (Tricco, Price & Bate 2016) and ch_factor = c_h,a
// instead of c_h^2.
inline Real psi_rate(Real ch_factor, Real div_b, Real psi, bool damped, Real damping_rate, bool continuity_term,
                     Real inv_omega_rho, Real continuity_sum) {
  Real rate = -ch_factor * div_b;
  if (damped) rate -= damping_rate * psi;
  if (continuity_term) rate += 0.5 * psi * inv_omega_rho * continuity_sum;
  return rate;
}

}  // namespace sphark::mhd
