#pragma once
// Monaghan (1992) artificial viscosity, the textbook choice for weakly compressible SPH:
//   Pi_ab = -alpha c_ab mu_ab / rho_ab,  mu_ab = h v_ab.x_ab / (r_ab^2 + eps h^2)  (v_ab.x_ab < 0)
//   dv_a/dt += - sum_b m_b Pi_ab grad_a W_ab
// It acts only on approaching pairs, conserves momentum exactly (Pi_ab = Pi_ba) and in the
// continuum limit equals a shear viscosity nu = alpha h c / (2 (D + 2)) (Monaghan 2005, eq. 4.9).
#include "sphark/core/types.hpp"

namespace sphark {

template <int D>
inline Vec<D> monaghan_viscosity_term(Real m_b, Real alpha, Real c_ab, Real rho_ab, Real h, const Vec<D>& x_ab,
                                      const Vec<D>& v_ab, const Vec<D>& grad_w) {
  const Real vr = v_ab.dot(x_ab);
  if (vr >= 0) return Vec<D>::Zero();
  const Real mu = h * vr / (x_ab.squaredNorm() + 0.01 * h * h);
  const Real pi_ab = -alpha * c_ab * mu / rho_ab;
  return -m_b * pi_ab * grad_w;
}

}  // namespace sphark
