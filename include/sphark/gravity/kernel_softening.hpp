#pragma once
// Kernel-softened gravity of one particle (Price & Monaghan 2007, MNRAS 374, 1347; "PM07"), 3D.
// A particle of mass m and smoothing length h is a mass distribution m W(r, h); its potential
// and force per unit G m are
//   phi(r, h)      = phi~(q) / h,    q = r / h           (-1/r exactly for r >= support * h)
//   dphi/dr (r, h) = phi~'(q) / h^2  = M(<r) / (m r^2),  M(<r) = m 4 pi int_0^r W r'^2 dr'   (PM07 §2)
//   dphi/dh (r, h) = -(phi~(q) + q phi~'(q)) / h^2       (0 for r >= support * h)
// so the acceleration of a test mass at separation x (|x| = r) from the particle is
// -G m dphi/dr x / r and its potential G m phi. The cubic-spline forms are PM07's Appendix A;
// every kernel here is derived from its piecewise-polynomial shape (softening_polynomials.hpp):
// CubicSpline<3>, QuinticSpline<3>, WendlandC2<3>, WendlandC4<3>, WendlandC6<3>.
#include <cmath>

#include "sphark/gravity/softening_polynomials.hpp"

namespace sphark {

template <class K>
struct KernelSoftening {
  using Table = softening_detail::SofteningTable<K>;
  static constexpr Real support = K::support;

  // phi(r, h): potential per unit G m (negative).
  static Real phi(Real r, Real h) {
    if (r >= support * h) return -1 / r;
    const Real q = r / h;
    const auto& p = piece(q);
    const Real inner = p.pot_const + q * q * softening_detail::horner<Table::n_terms>(p.potential.c, q);
    return (p.mass_const == 0 ? inner : inner - p.mass_const / q) / h;
  }
  // dphi/dr (r, h) (positive: the force is attractive).
  static Real dphi_dr(Real r, Real h) {
    if (r >= support * h) return 1 / (r * r);
    const Real q = r / h;
    const auto& p = piece(q);
    const Real poly = q * softening_detail::horner<Table::n_terms>(p.force.c, q);
    return (p.mass_const == 0 ? poly : poly + p.mass_const / (q * q)) / (h * h);
  }
  // (dphi/dr) / r, finite at r = 0: the pair-force coefficient (acceleration = -G m (this) x).
  static Real force_over_r(Real r, Real h) {
    if (r >= support * h) return 1 / (r * r * r);
    const Real q = r / h;
    const auto& p = piece(q);
    const Real poly = softening_detail::horner<Table::n_terms>(p.force.c, q);
    return (p.mass_const == 0 ? poly : poly + p.mass_const / (q * q * q)) / (h * h * h);
  }
  // dphi/dh (r, h) at fixed r: what the grad-h term zeta sums (PM07 §3).
  static Real dphi_dh(Real r, Real h) {
    if (r >= support * h) return 0;
    const Real q = r / h;
    const auto& p = piece(q);
    return -(p.pot_const + q * q * softening_detail::horner<Table::n_terms>(p.dphi_dh.c, q)) / (h * h);
  }

  // The polynomial piece that holds q (q < support).
  static const softening_detail::SofteningPiece& piece(Real q) {
    int k = 0;
    while (k + 1 < Table::count && q >= Table::pieces[k].end) ++k;
    return Table::pieces[k];
  }
};

// A particle's potential on itself per unit G: m phi(0, h) (the b = a term of PM07's sum; the
// self energy of its smoothed mass), 0 for an unsoftened point mass (h = 0).
template <class K>
inline Real self_potential(Real m, Real h) {
  return h > 0 ? m * KernelSoftening<K>::phi(0, h) : 0;
}

// The symmetric pair interaction of PM07 (§3): phi_ab = (phi(r, h_a) + phi(r, h_b)) / 2 and the
// force coefficient ((dphi/dr)(r, h_a) + (dphi/dr)(r, h_b)) / (2 r), bitwise symmetric in (h_a, h_b).
// Acceleration of a: -G m_b force_over_r (x_a - x_b); potential at a: G m_b phi.
struct PairGravity {
  Real force_over_r;
  Real phi;
};

// One particle (smoothing length h, h_inv = 1/h) seen at r (inv_r = 1/r, or 0 at r = 0): on
// its piece, force_over_r = f(q) / h^3 + A_k / r^3 and phi = v(q) / h - A_k / r (A_k = 0 on the
// innermost piece, so r = 0 is fine): one piece lookup, no division.
template <class K>
inline PairGravity one_side(Real r, Real inv_r, Real h, Real h_inv) {
  if (r >= K::support * h) return {inv_r * inv_r * inv_r, -inv_r};
  using Table = typename KernelSoftening<K>::Table;
  const Real q = r * h_inv;
  const softening_detail::SofteningPiece& p = KernelSoftening<K>::piece(q);
  const Real f = softening_detail::horner<Table::n_terms>(p.force.c, q);
  const Real v = p.pot_const + q * q * softening_detail::horner<Table::n_terms>(p.potential.c, q);
  const Real h_inv3 = h_inv * h_inv * h_inv;
  if (p.mass_const == 0) return {f * h_inv3, v * h_inv};
  return {f * h_inv3 + p.mass_const * (inv_r * inv_r * inv_r), v * h_inv - p.mass_const * inv_r};
}

// The pair at squared separation r2, with both smoothing lengths and their inverses.
template <class K>
inline PairGravity softened_pair(Real r2, Real h_a, Real h_a_inv, Real h_b, Real h_b_inv) {
  const Real reach = K::support * (h_a > h_b ? h_a : h_b);
  if (r2 >= reach * reach) {
    const Real inv_r = 1 / std::sqrt(r2);
    return {inv_r * inv_r * inv_r, -inv_r};
  }
  const Real r = std::sqrt(r2), inv_r = r > 0 ? 1 / r : 0;
  const PairGravity a = one_side<K>(r, inv_r, h_a, h_a_inv), b = one_side<K>(r, inv_r, h_b, h_b_inv);
  return {0.5 * (a.force_over_r + b.force_over_r), 0.5 * (a.phi + b.phi)};
}

template <class K>
inline PairGravity softened_pair(Real r2, Real h_a, Real h_b) {
  return softened_pair<K>(r2, h_a, 1 / h_a, h_b, 1 / h_b);
}

}  // namespace sphark
