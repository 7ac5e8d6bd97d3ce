#pragma once
// Density diffusion for weakly compressible SPH (delta-SPH).
//
// Molteni & Colagrossi (2009), Comput. Phys. Commun. 180, eq. (8):
//   drho_a/dt += delta h c_s sum_b V_b psi_ab . grad_a W_ab,   psi_ab = 2 (rho_a - rho_b) x_ab / r_ab^2
// Antuono et al. (2010), Comput. Phys. Commun. 181, eq. (11), subtracts the part a linear
// density field produces, using the renormalised gradients <grad rho>^L:
//   psi_ab = 2 (rho_a - rho_b) x_ab / r_ab^2 - (<grad rho>^L_a + <grad rho>^L_b)
// Without that correction the term is first order in grad rho wherever the kernel support is
// truncated (free surfaces), where it pumps density at a rate ~ delta c_s |grad rho|; with it,
// psi_ab . grad_a W_ab vanishes pair by pair for any linear density field.
// Either form is antisymmetric under a <-> b (times V_a V_b), so sum_a V_a drho_a/dt = 0.
#include <type_traits>

#include "sphark/core/types.hpp"

namespace sphark {

template <int D>
inline Real density_diffusion_term(Real volume_b, Real rho_a, Real rho_b, const Vec<D>& grad_rho_a,
                                   const Vec<D>& grad_rho_b, const Vec<D>& x_ab, const Vec<D>& grad_w) {
  const Vec<D> psi_ab = 2.0 * (rho_a - rho_b) * x_ab / x_ab.squaredNorm() - (grad_rho_a + grad_rho_b);
  return volume_b * psi_ab.dot(grad_w);
}

// The same summand for a radial kernel gradient grad_w = F x_ab (F = (dW/dr)/r), where
// x_ab . grad_w / r_ab^2 = F:  V_b psi_ab . grad_w = V_b (2 (rho_a - rho_b) F - (<grad rho>_a + <grad rho>_b) . grad_w)
// (no division; the pair loops' form, for Real or lanes). Uncorrected: both gradients zero.
template <class S, class V>
inline S density_diffusion_term_radial(S volume_b, std::type_identity_t<S> rho_a, std::type_identity_t<S> rho_b,
                                       const std::type_identity_t<V>& grad_rho_a,
                                       const std::type_identity_t<V>& grad_rho_b, std::type_identity_t<S> F,
                                       const V& grad_w) {
  return volume_b * (2.0 * (rho_a - rho_b) * F - (grad_rho_a + grad_rho_b).dot(grad_w));
}
template <class S>
inline S density_diffusion_term_radial(S volume_b, std::type_identity_t<S> rho_a, std::type_identity_t<S> rho_b,
                                       std::type_identity_t<S> F) {
  return volume_b * (2.0 * (rho_a - rho_b) * F);
}

}  // namespace sphark
