// The SPMHD RHS's momentum budget (diagnostics, issue #16): the total force and the part the
// tensile-instability correction (seed 000, eq. (9)) injects; see SpmhdScheme::momentum_budget.
#include <cmath>
#include <limits>

#include "sphark/kernels/kernel_list.hpp"
#include "sphark/operators/mhd_operators.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"
#include "sphark/schemes/spmhd/unit_kernel.hpp"

namespace sphark {

template <int D, class K>
typename SpmhdScheme<D, K>::MomentumBudget SpmhdScheme<D, K>::momentum_budget(Real t, const Real* y) {
  MomentumBudget m;
  if (!opt_.evolve_particles || evaluate(t, y) != 0) {
    m.total.setConstant(std::numeric_limits<Real>::quiet_NaN());
    m.tensile = m.total;
    return m;
  }
  const Real* dv_dt = scratch_.data() + layout_.offset(Field::Velocity);
  for (std::size_t a = 0; a < n_; ++a) m.total += m_[a] * Eigen::Map<const Vec<D>>(dv_dt + D * a);
  if constexpr (D == 3) {
    const std::size_t ns = layout_.particles(Species::Sink);
    for (std::size_t k = 0; k < ns; ++k)
      m.total += y[layout_.offset(Species::Sink, Field::Mass) + k] *
                 Eigen::Map<const Vec<3>>(scratch_.data() + layout_.offset(Species::Sink, Field::Velocity) + 3 * k);
  }
  if (!opt_.subtract_monopole_force) return m;
  const NeighbourList& L = ns_.list();
  const MinimumImage<D> image(ns_.box());
  for (std::size_t a = 0; a < n_; ++a) {  // slots, serial: a fixed summation order
    Real S = 0;  // eq. (9)'s symmetric divergence
    const Eigen::Map<const Vec<D>> oB_a(&b_over_omega_rho2_[3 * a]);
    for (std::size_t k = L.begin(a); k < L.end(a); ++k) {
      const std::size_t b = L.indices[k];
      const Vec<D> x_ab = image(x_.data() + D * a, x_.data() + D * b);
      const Real r = x_ab.norm();
      if (r >= K::support * std::max(h_[a], h_[b]) || r == 0) continue;
      // the force pass's kernel gradients (spmhd_forces.cpp)
      const Vec<D> g_a = grad_scale_[a] * UnitKernel<K>::f_over_r(r * inv_h_[a], h_[a] / r) * x_ab;
      const Vec<D> g_b = grad_scale_[b] * UnitKernel<K>::f_over_r(r * inv_h_[b], h_[b] / r) * x_ab;
      S += mhd::monopole_term(ms_[b], oB_a, g_a, Eigen::Map<const Vec<D>>(&b_over_omega_rho2_[3 * b]), g_b);
    }
    m.tensile -= ms_[a] * S * Eigen::Map<const Vec<3>>(&B_[3 * a]).template head<D>();
  }
  return m;
}

#define SPHARK_SPMHD_MOMENTUM(D, K) \
  template SpmhdScheme<D, K>::MomentumBudget SpmhdScheme<D, K>::momentum_budget(Real, const Real*);
#define SPHARK_SPMHD_MOMENTUM_2D_3D(K) SPHARK_SPMHD_MOMENTUM(2, K<2>) SPHARK_SPMHD_MOMENTUM(3, K<3>)
SPHARK_KERNELS(SPHARK_SPMHD_MOMENTUM_2D_3D)
#undef SPHARK_SPMHD_MOMENTUM_2D_3D
#undef SPHARK_SPMHD_MOMENTUM

}  // namespace sphark
