// The SPMHD RHS's momentum budget (diagnostics, issue #16): the total force and the part the
// tensile-instability correction (seed 000, eq. (9)) injects; see SpmhdScheme::momentum_budget.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "sphark/kernels/kernel_list.hpp"
#include "sphark/operators/mhd_operators.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"

namespace sphark {

// The share of eq. (9) the force pass applies to each slot: none within
// opt_.tensile_sink_exclusion of a sink (minimum image); with opt_.tensile_beta_none > 0, all of
// it where beta = 2P/|B|^2 < tensile_beta_full, none above tensile_beta_none, linear between
// (Phantom's switch). nullptr when it is applied whole everywhere.
template <int D, class K>
const Real* SpmhdScheme<D, K>::tensile_weights(const Real* y) {
  const std::size_t ns = layout_.particles(Species::Sink);
  const bool near_sinks = opt_.tensile_sink_exclusion > 0 && ns > 0, by_beta = opt_.tensile_beta_none > 0;
  if (!opt_.subtract_monopole_force || !(near_sinks || by_beta)) return nullptr;
  tensile_weight_.assign(n_, 1.0);
  if (by_beta) {
    const Real full = opt_.tensile_beta_full, none = opt_.tensile_beta_none;
    for (std::size_t a = 0; a < n_; ++a) {
      const Real B2 = Eigen::Map<const Vec<3>>(&B_[3 * a]).squaredNorm();
      const Real beta = B2 > 0 ? 2 * P_[a] / B2 : std::numeric_limits<Real>::infinity();
      tensile_weight_[a] = beta < full ? 1.0 : beta < none ? (none - beta) / (none - full) : 0.0;
    }
  }
  if (near_sinks) {
    const Real r2 = opt_.tensile_sink_exclusion * opt_.tensile_sink_exclusion;
    const Real* xs = y + layout_.offset(Species::Sink, Field::Position);
    const MinimumImage<D> image(ns_.box());
    for (std::size_t a = 0; a < n_; ++a)
      for (std::size_t k = 0; k < ns; ++k)
        if (image(x_.data() + D * a, xs + 3 * k).squaredNorm() < r2) tensile_weight_[a] = 0;
  }
  return tensile_weight_.data();
}

template <int D, class K>
typename SpmhdScheme<D, K>::MomentumBudget SpmhdScheme<D, K>::momentum_budget(Real t, const Real* y) {
  MomentumBudget m;
  if (halo_) throw std::logic_error("SpmhdScheme::momentum_budget: not for a distributed scheme");
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
  const MinimumImage<D> image(ns_.box());
  // B / (Omega rho^2) and the force pass's kernel gradient (spmhd_pair_row.hpp): f_over_r(r, h)
  // = unit_f_over_r(r / h, h / r) / h^(D+2)
  std::vector<Real> bo(3 * n_);
  for (std::size_t a = 0; a < n_; ++a)
    for (int k = 0; k < 3; ++k) bo[3 * a + k] = B_[3 * a + k] / (omega_[a] * rho_[a] * rho_[a]);
  std::vector<Real> h_power(n_);  // h^(D+2) per slot, once instead of once per pair
  for (std::size_t a = 0; a < n_; ++a) h_power[a] = std::pow(h_[a], D + 2);
  const auto gradient_factor = [&](std::size_t a, Real r) {
    return K::unit_f_over_r(r / h_[a], h_[a] / r) / h_power[a];
  };
  const Real* weight = tensile_weights(y);
  // Summed in particle (state) order, each particle's neighbours too: serial, and independent of
  // the slots' numbering, which changes at every list build (a restarted run builds its lists
  // elsewhere than the uninterrupted one).
  std::vector<std::uint32_t> slot_of(n_), near;
  for (std::size_t a = 0; a < n_; ++a) slot_of[perm_[a]] = static_cast<std::uint32_t>(a);
  for (std::size_t p = 0; p < n_; ++p) {
    const std::size_t a = slot_of[p];
    if (weight && weight[a] == 0) continue;
    Real S = 0;  // eq. (9)'s symmetric divergence
    const Eigen::Map<const Vec<D>> oB_a(&bo[3 * a]);
    const std::size_t n_near = entries_within_reach(a, image, near);
    std::sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(n_near),
              [this](std::uint32_t u, std::uint32_t v) { return perm_[u] < perm_[v]; });
    for (std::size_t e = 0; e < n_near; ++e) {
      const std::size_t b = near[e];
      const Vec<D> x_ab = image(x_.data() + D * a, x_.data() + D * b);
      const Real r = x_ab.norm(), reach = K::support * std::max(h_[a], h_[b]);
      if (r >= reach || r == 0) continue;
      const Vec<D> g_a = gradient_factor(a, r) * x_ab, g_b = gradient_factor(b, r) * x_ab;
      S += mhd::monopole_term(ms_[b], oB_a, g_a, Eigen::Map<const Vec<D>>(&bo[3 * b]), g_b);
    }
    m.tensile -= ms_[a] * (weight ? weight[a] * S : S) * Eigen::Map<const Vec<3>>(&B_[3 * a]).template head<D>();
  }
  return m;
}

#define SPHARK_SPMHD_MOMENTUM(D, K)                                                              \
  template SpmhdScheme<D, K>::MomentumBudget SpmhdScheme<D, K>::momentum_budget(Real, const Real*); \
  template const Real* SpmhdScheme<D, K>::tensile_weights(const Real*);
#define SPHARK_SPMHD_MOMENTUM_2D_3D(K) SPHARK_SPMHD_MOMENTUM(2, K<2>) SPHARK_SPMHD_MOMENTUM(3, K<3>)
SPHARK_KERNELS(SPHARK_SPMHD_MOMENTUM_2D_3D)
#undef SPHARK_SPMHD_MOMENTUM_2D_3D
#undef SPHARK_SPMHD_MOMENTUM

}  // namespace sphark
