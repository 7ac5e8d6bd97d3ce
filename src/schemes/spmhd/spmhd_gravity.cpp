// Self-gravity of the SPMHD gas (3D): the kernel-softened pair forces with softening length =
// each particle's own h, from the tree or direct summation (gravity/self_gravity.hpp; the tree
// uses the positions as given: isolated gravity, see docs/gravity.md). The gravitational grad-h
// term that makes the force the gradient of the energy while h adapts (Price & Monaghan 2007,
// §3; gravity/gravity_grad_h.hpp),
//   a_a += -(G/2) sum_b m_b [ zeta_a/Omega_a grad_a W_ab(h_a) + zeta_b/Omega_b grad_a W_ab(h_b) ]
//   zeta_a = (dh_a/drho_a) sum_b m_b dphi(r_ab, h_a)/dh_a   (b = a included),
// is added by the MHD pair loop, as an isotropic stress -(G/2) zeta/Omega (pair_loop_arrays,
// spmhd_forces.cpp); zeta is summed in the density solve, over its candidates at the solved h
// (spmhd_density.cpp). Each particle writes only its own acceleration: results independent of
// the thread count.
//
// The tree and every sum of the solvers depend on the order of their input, and the slots' order
// depends on when the lists were last built (the call history). So the solvers see the sources in
// particle (state) order, and their accelerations and potentials stay in particle order: the same
// y gives the same gravity bit for bit, whatever ran before (a restart continues bit for bit).
#include <algorithm>
#include <cmath>
#include <limits>

#include "sphark/core/profile.hpp"
#include "sphark/gravity/gravity_grad_h.hpp"
#include "sphark/kernels/kernel_list.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"

namespace sphark {

// Slot a's neighbours b (list order) that can be within support * max(h_a, h_b): a branch-free
// pass over the row (about half of a row lies beyond, in no predictable pattern), so that the
// pair loop after it rarely branches. Keeps every b with |x_ab|^2 < reach^2 (1 + slack): with
// slack 0 exactly those, with a little a few just beyond (for a loop that checks again).
template <int D, class K>
std::size_t SpmhdScheme<D, K>::entries_within_reach(std::size_t a, const MinimumImage<D>& image,
                                                    std::vector<std::uint32_t>& near, Real slack) const {
  const NeighbourList& L = ns_.list();
  const std::size_t begin = L.begin(a), count = L.count(a);
  if (near.size() < count) near.resize(count + count / 4);
  const Real* x = x_.data();
  std::size_t n = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint32_t b = L.indices[begin + k];
    const Real reach = K::support * std::max(h_[a], h_[b]);
    near[n] = b;
    n += image(x + D * a, x + D * b).squaredNorm() < reach * reach * (1 + slack);
  }
  return n;
}

// Every particle's field when the last rhs() computed it at these positions and no particle
// moved, left or came since (full_rhs_at_x_: a leapfrog's corrector iteration, diagnostics after
// a step): the field depends on the positions, masses and h alone, so it is added again as it was
// (the potentials and energy too, before the sinks' part: sink_pass adds that afresh).
template <int D, class K>
void SpmhdScheme<D, K>::gravity_pass(Real* ydot, const std::vector<std::uint32_t>* only) {
  if constexpr (D == 3) {
    ScopedPhase timer(Phase::Forces);
    const bool same_field = !only && full_rhs_at_x_;
    if (same_field) {
      std::copy(self_potential_.begin(), self_potential_.end(), gravity_potential_.begin());
      potential_energy_ = self_potential_energy_;
      ++version_;  // (particle-order caches of the potentials)
    } else {
      compute_gravity(only);
    }
    Real* dv_dt = ydot + layout_.offset(Field::Velocity);
    const std::size_t rows = only ? only->size() : n_;
    for (std::size_t i = 0; i < rows; ++i) {
      const std::size_t p = perm_[only ? (*only)[i] : i];
      Eigen::Map<Vec<3>>(dv_dt + 3 * p) += Eigen::Map<const Vec<3>>(gravity_acc_.data() + 3 * p);
    }
  }
}

template <int D, class K>
void SpmhdScheme<D, K>::compute_gravity(const std::vector<std::uint32_t>* only) {
  if constexpr (D == 3) {
    ++gravity_solves_;
    gravity_x_.resize(3 * n_);
    gravity_h_.resize(n_);
    for (std::size_t s = 0; s < n_; ++s) {
      const std::size_t p = perm_[s];
      std::copy_n(x_.data() + 3 * s, 3, gravity_x_.data() + 3 * p);
      gravity_h_[p] = h_[s];
    }
    GravitySources sources = gravity_sources();
    if (only) {  // the field at the active rows only (particle order); the others' NaN, the energy NaN
      gravity_wanted_.assign(n_, 0);
      for (std::uint32_t a : *only) gravity_wanted_[perm_[a]] = 1;
      sources.wanted = gravity_wanted_.data();
    }
    potential_energy_ = gravity_->compute(sources, gravity_acc_.data(), gravity_potential_.data());
    ++version_;  // the potentials changed (particle-order caches)
    if (!only) self_potential_.assign(gravity_potential_.begin(), gravity_potential_.end()), self_potential_energy_ = potential_energy_;
  }
}

// min_a force_courant sqrt(h_a / |dv_a/dt|) of a derivative (the force criterion; +inf if a = 0).
template <int D, class K>
Real SpmhdScheme<D, K>::force_time_step(const Real* ydot) const {
  Real dt = std::numeric_limits<Real>::infinity();
  for (std::size_t a = 0; a < n_; ++a) dt = std::min(dt, force_step(a, ydot));
  return dt;
}

template <int D, class K>
Real SpmhdScheme<D, K>::force_step(std::size_t a, const Real* ydot) const {
  const Real acc = Eigen::Map<const Vec<D>>(ydot + layout_.offset(Field::Velocity) + D * perm_[a]).norm();
  return acc > 0 ? opt_.force_courant * std::sqrt(h_[a] / acc) : std::numeric_limits<Real>::infinity();
}

#define SPHARK_SPMHD_GRAVITY(D, K)                          \
  template std::size_t SpmhdScheme<D, K>::entries_within_reach(std::size_t, const MinimumImage<D>&,            \
                                                                std::vector<std::uint32_t>&, Real) const;      \
  template void SpmhdScheme<D, K>::gravity_pass(Real*, const std::vector<std::uint32_t>*); \
  template void SpmhdScheme<D, K>::compute_gravity(const std::vector<std::uint32_t>*);        \
  template Real SpmhdScheme<D, K>::force_time_step(const Real*) const; \
  template Real SpmhdScheme<D, K>::force_step(std::size_t, const Real*) const;
#define SPHARK_SPMHD_GRAVITY_2D_3D(K) SPHARK_SPMHD_GRAVITY(2, K<2>) SPHARK_SPMHD_GRAVITY(3, K<3>)
SPHARK_KERNELS(SPHARK_SPMHD_GRAVITY_2D_3D)
#undef SPHARK_SPMHD_GRAVITY_2D_3D
#undef SPHARK_SPMHD_GRAVITY

}  // namespace sphark
