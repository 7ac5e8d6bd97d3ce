// The multirate interface of the SPMHD scheme (issue #17; integrate/ode_system.hpp): the
// derivatives of a subset of the particles, each against all its neighbours, and each
// particle's own stable step.
//
// Work: the pair loops (seed 000 §II: the force pass, and with self-gravity the grad-h term of
// Price & Monaghan 2007) run over the active gas particles only. What the active particles'
// rows read from their neighbours is computed for all particles: density, h and Omega (the
// summation, memoised on the exact positions, so repeated subset calls at one state solve it
// once), P, the signal speeds; the gravity tree (one walk for all targets) and the sink forces
// are computed for all and kept for the active particles. So a fast evaluation costs the
// active rows plus O(N) per-particle work, and a tree walk with gravity.
#include <algorithm>
#include <stdexcept>
#include <cmath>
#include <limits>

#include "sphark/core/profile.hpp"
#include "sphark/integrate/callback_errors.hpp"
#include "sphark/kernels/kernel_list.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"

namespace sphark {

template <int D, class K>
int SpmhdScheme<D, K>::rhs_subset(Real t, const Real* y, std::span<const std::size_t> active, Real* ydot) {
  if (halo_) throw std::logic_error("SpmhdScheme::rhs_subset: not for a distributed scheme");
  ++rhs_calls_;
  ScopedPhase timer(Phase::Rhs);
  if (const int rc = prepare(t, y); rc != 0) return rc;
  std::fill(ydot, ydot + layout_.size(), 0.0);
  slot_of_.resize(n_);
  for (std::size_t s = 0; s < n_; ++s) slot_of_[perm_[s]] = static_cast<std::uint32_t>(s);
  active_slots_.clear();
  for (std::size_t i : active)
    if (i < n_) active_slots_.push_back(slot_of_[i]);
  std::sort(active_slots_.begin(), active_slots_.end());  // rows in slot (memory) order
  force_pass(y, ydot, &active_slots_);
  if (opt_.self_gravity) gravity_pass(ydot, &active_slots_);
  if (opt_.sink_particles && layout_.particles(Species::Sink) > 0) {
    subset_scratch_.assign(layout_.size(), 0.0);
    sink_pass(y, subset_scratch_.data());  // the sink forces on all; kept for the active particles
    const std::vector<std::size_t> owner = entry_particles();
    std::vector<char> is_active(n_ + layout_.particles(Species::Sink), 0);
    for (std::size_t i : active) is_active.at(i) = 1;
    for (std::size_t k = 0; k < owner.size(); ++k)
      if (is_active[owner[k]]) ydot[k] += subset_scratch_[k];
  }
  return 0;
}

// Neighbours' steps bound each other: a particle's step is at most kNeighbourStepFactor times
// that of any particle within the kernel support (the time-step limiter of Saitoh & Makino 2009,
// ApJ 697 L99, factor 4), so that a long-stepping particle is woken up (block steps) or made fast
// (MRIStep) before a shock from a short-stepping neighbour reaches it.
constexpr Real kNeighbourStepFactor = 4;

template <int D, class K>
int SpmhdScheme<D, K>::particle_stable_dt(Real t, const Real* y, const Real* ydot, Real* dt) {
  if (halo_) throw std::logic_error("SpmhdScheme::particle_stable_dt: not for a distributed scheme");
  if (stable_steps(t, y, ydot, courant_steps_, force_steps_) != 0) return 1;  // error_ says why
  std::vector<Real>& own = courant_steps_;  // particle order
  for (std::size_t a = 0; a < n_; ++a) own[a] = std::min(courant_steps_[a], force_steps_[a]);
  std::vector<Real>& own_of_slot = force_steps_;  // reused: slot order, read along the rows
  for (std::size_t a = 0; a < n_; ++a) own_of_slot[a] = own[perm_[a]];
  const NeighbourList& L = ns_.list();  // slots; stable_steps prepared the lists for y
  const MinimumImage<D> image(ns_.box());
  const Real* x = x_.data();
#pragma omp parallel for schedule(dynamic, 64)
  for (std::size_t a = 0; a < n_; ++a) {
    Real least = std::numeric_limits<Real>::infinity();
    for (std::size_t k = L.begin(a); k < L.end(a); ++k) {
      const std::size_t b = L.indices[k];
      if (!(own_of_slot[b] < least)) continue;  // cannot lower the minimum: no distance needed
      const Real reach = K::support * std::max(h_[a], h_[b]);
      if (image(x + D * a, x + D * b).squaredNorm() < reach * reach) least = own_of_slot[b];
    }
    dt[perm_[a]] = std::min(own_of_slot[a], kNeighbourStepFactor * least);
  }
  // A sink pulls on every gas particle, hardest on the closest ones, which orbit it on the
  // shortest steps: it takes the shortest gas step (as in the global leapfrog, whose one step
  // is that minimum), so its pair forces with the gas are sampled as often as theirs.
  const Real shortest = n_ > 0 ? *std::min_element(dt, dt + n_) : std::numeric_limits<Real>::infinity();
  std::fill(dt + n_, dt + num_particles(), shortest);  // sinks
  return 0;
}

#define SPHARK_SPMHD_SUBSETS(D, K)                                                                        \
  template int SpmhdScheme<D, K>::rhs_subset(Real, const Real*, std::span<const std::size_t>, Real*);   \
  template int SpmhdScheme<D, K>::particle_stable_dt(Real, const Real*, const Real*, Real*);
#define SPHARK_SPMHD_SUBSETS_2D_3D(K) SPHARK_SPMHD_SUBSETS(2, K<2>) SPHARK_SPMHD_SUBSETS(3, K<3>)
SPHARK_KERNELS(SPHARK_SPMHD_SUBSETS_2D_3D)
#undef SPHARK_SPMHD_SUBSETS_2D_3D
#undef SPHARK_SPMHD_SUBSETS

}  // namespace sphark
