#pragma once
// Density diffusion of delta-SPH (Molteni & Colagrossi 2009, Comput. Phys. Commun. 180, eq. 8):
//   drho_a/dt += 2 delta h c_s sum_b V_b (rho_a - rho_b) (x_ab . grad_a W_ab) / r_ab^2
// A discrete Laplacian of rho scaled by delta h c_s: it removes the high-frequency pressure
// noise of the weakly compressible scheme while conserving mass (antisymmetric in a, b with
// m_b = rho_b V_b and equal masses). x_ab . grad_a W_ab = r dW/dr <= 0, so it smooths.
#include "sphark/core/types.hpp"

namespace sphark {

template <int D>
inline Real density_diffusion_term(Real volume_b, Real rho_a, Real rho_b, const Vec<D>& x_ab, const Vec<D>& grad_w) {
  const Real r2 = x_ab.squaredNorm();
  return 2.0 * volume_b * (rho_a - rho_b) * x_ab.dot(grad_w) / r2;
}

}  // namespace sphark
