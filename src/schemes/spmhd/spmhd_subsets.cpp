// The multirate interface of the SPMHD scheme (issue #17; integrate/ode_system.hpp): the
// derivatives of a subset of the particles, each against all its neighbours, and each
// particle's own stable step.
//
// Work: the pair loops (seed 000 §II: the force pass, and with self-gravity the grad-h term of
// Price & Monaghan 2007) run over the active gas particles only, and so does the density / h
// solve (4)-(5): over the active particles and (SpmhdOptions::subset_density Solved) their list
// neighbours, whose values the active rows read, or (Predicted) over the active particles only,
// the neighbours' h predicted and rho from it (memoised per slot on the exact positions:
// repeated calls at one state solve each slot once, and a full rhs() there solves only the
// slots not yet solved). Each solve starts from
// its slot's own last iterate and time. Computed for all particles and kept for the active
// ones: the neighbour lists (Verlet, rebuilt for all when some list is too short), P and the
// signal speeds (O(N) arithmetic; the global c_h is the largest fast speed, of the unsolved slots
// as last solved), the gravity tree (built for all, walked for the active targets; the unsolved
// slots soften with their predicted h, which no active pair reads) and the sink forces.
// So a fast evaluation costs the active rows and their neighbours' solves, O(N) arithmetic, and
// the tree and list builds.
#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>

#include "sphark/core/profile.hpp"
#include "sphark/integrate/callback_errors.hpp"
#include "sphark/kernels/kernel_list.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"

namespace sphark {
namespace {
// While alive, the scheme's prepare() serves the particles `active` only (serve_particles_).
class ServeOnly {
 public:
  ServeOnly(std::span<const std::size_t>& served, std::span<const std::size_t> active) : served_(served) { served_ = active; }
  ~ServeOnly() { served_ = {}; }
  ServeOnly(const ServeOnly&) = delete;
  ServeOnly& operator=(const ServeOnly&) = delete;

 private:
  std::span<const std::size_t>& served_;
};
}  // namespace

template <int D, class K>
void SpmhdScheme<D, K>::slots_of(std::span<const std::size_t> particles, std::vector<std::uint32_t>& slots) {
  slot_of_.resize(n_);
  for (std::size_t s = 0; s < n_; ++s) slot_of_[perm_[s]] = static_cast<std::uint32_t>(s);
  slots.clear();
  for (const std::size_t i : particles)
    if (i < n_) slots.push_back(slot_of_[i]);
}

template <int D, class K>
int SpmhdScheme<D, K>::rhs_subset(Real t, const Real* y, std::span<const std::size_t> active, Real* ydot) {
  if (halo_) throw std::logic_error("SpmhdScheme::rhs_subset: not for a distributed scheme");
  full_rhs_at_x_ = false;  // (the others' potentials are not computed)
  // every particle active (a block cycle's last event): the gravity field of all, as rhs()'s
  const bool every_particle = active.size() == num_particles();
  ++rhs_calls_;
  ScopedPhase timer(Phase::Rhs);
  {
    const ServeOnly served(serve_particles_, active);
    if (const int rc = prepare(t, y); rc != 0) return rc;
  }
  std::fill(ydot, ydot + layout_.size(), 0.0);
  slots_of(active, active_slots_);
  std::sort(active_slots_.begin(), active_slots_.end());  // rows in slot (memory) order
  force_pass(y, ydot, &active_slots_);
  if (opt_.self_gravity) gravity_pass(ydot, every_particle ? nullptr : &active_slots_);
  if (opt_.sink_particles && layout_.particles(Species::Sink) > 0) {
    subset_scratch_.assign(layout_.size(), 0.0);
    sink_pass(y, subset_scratch_.data());  // the sink forces on all; kept for the active particles
    const std::size_t sinks = layout_.particles(Species::Sink);
    if (entry_owner_counts_ != std::pair{n_, sinks}) entry_owner_ = entry_particles(), entry_owner_counts_ = {n_, sinks};
    is_active_.assign(n_ + sinks, 0);
    for (std::size_t i : active) is_active_.at(i) = 1;
    for (std::size_t k = 0; k < entry_owner_.size(); ++k)
      if (is_active_[entry_owner_[k]]) ydot[k] += subset_scratch_[k];
  }
  if (every_particle) note_full_evaluation(y);
  return 0;
}

// Neighbours' steps bound each other: a particle's step is at most kNeighbourStepFactor times
// that of any particle within the kernel support (the time-step limiter of Saitoh & Makino 2009,
// ApJ 697 L99, factor 4), so that a long-stepping particle is woken up (block steps) or made fast
// (MRIStep) before a shock from a short-stepping neighbour reaches it.
constexpr Real kNeighbourStepFactor = 4;

// Each gas particle's own step min(Courant, force criterion), read by slot (own_of_slot_),
// after stable_steps at (t, y) (which prepares the lists for y).
template <int D, class K>
int SpmhdScheme<D, K>::own_steps_by_slot(Real t, const Real* y, const Real* ydot) {
  if (halo_) throw std::logic_error("SpmhdScheme: per-particle steps are not for a distributed scheme");
  if (prepare_steps(t, y, ydot) != 0) return 1;  // error_ says why
  own_of_slot_.resize(n_);
  for (std::size_t a = 0; a < n_; ++a)
    if (std::isnan(own_of_slot_[a] = own_step(a, ydot))) return 1;
  return 0;
}

// The least own step among slot a's neighbours within the kernel support (either h).
template <int D, class K>
Real SpmhdScheme<D, K>::least_neighbour_step(std::size_t a, const MinimumImage<D>& image) const {
  const NeighbourList& L = ns_.list();
  const Real* x = x_.data();
  Real least = std::numeric_limits<Real>::infinity();
  for (std::size_t k = L.begin(a); k < L.end(a); ++k) {
    const std::size_t b = L.indices[k];
    if (!(own_of_slot_[b] < least)) continue;  // cannot lower the minimum: no distance needed
    const Real reach = K::support * std::max(h_[a], h_[b]);
    if (image(x + D * a, x + D * b).squaredNorm() < reach * reach) least = own_of_slot_[b];
  }
  return least;
}

template <int D, class K>
int SpmhdScheme<D, K>::particle_stable_dt(Real t, const Real* y, const Real* ydot, Real* dt) {
  if (own_steps_by_slot(t, y, ydot) != 0) return 1;
  const MinimumImage<D> image(ns_.box());
#pragma omp parallel for schedule(dynamic, 64)
  for (std::size_t a = 0; a < n_; ++a)
    dt[perm_[a]] = std::min(own_of_slot_[a], kNeighbourStepFactor * least_neighbour_step(a, image));
  // A sink pulls on every gas particle, hardest on the closest ones, which orbit it on the
  // shortest steps: it takes the shortest gas step (as in the global leapfrog, whose one step
  // is that minimum), so its pair forces with the gas are sampled as often as theirs.
  const Real shortest = n_ > 0 ? *std::min_element(dt, dt + n_) : std::numeric_limits<Real>::infinity();
  std::fill(dt + n_, dt + num_particles(), shortest);  // sinks
  return 0;
}

// Slot a's neighbours within support * max(h_a, h_b): the row of the last subset force pass at
// this state if it had a (its interacting neighbours: the same, but for a itself), else a pass
// over a's list.
template <int D, class K>
std::span<const std::uint32_t> SpmhdScheme<D, K>::neighbours_within_reach(std::size_t a, const MinimumImage<D>& image) {
  if (interacting_rows_valid_) {
    const auto row = std::lower_bound(active_slots_.begin(), active_slots_.end(), static_cast<std::uint32_t>(a));
    if (row != active_slots_.end() && *row == a) return interacting_rows_[static_cast<std::size_t>(row - active_slots_.begin())];
  }
  const std::size_t n = entries_within_reach(a, image, limiter_near_, 0);  // (may grow limiter_near_)
  return {limiter_near_.data(), n};
}

// After an evaluation of `active`: the limiter from the active side only (Phantom's wake-up,
// Price et al. 2018 §2.3.4: a neighbour whose step is more than 4 x an active particle's own).
template <int D, class K>
int SpmhdScheme<D, K>::active_stable_dt(Real t, const Real* y, const Real* ydot, std::span<const std::size_t> active,
                                        Real* dt) {
  if (active.size() >= num_particles()) return particle_stable_dt(t, y, ydot, dt);
  const ServeOnly served(serve_particles_, active);  // (own steps are read for them and their neighbours)
  if (prepare_steps(t, y, ydot) != 0) return 1;  // error_ says why
  // Own steps of the slots read only (the active ones, their neighbours within reach, the solved
  // ones: most particles are read by no active row), each at its first read.
  own_of_slot_.assign(n_, std::numeric_limits<Real>::quiet_NaN());
  bool finite = true;
  const auto own = [&](std::size_t b) {
    Real& step = own_of_slot_[b];
    if (std::isnan(step)) finite = !std::isnan(step = own_step(b, ydot)) && finite;  // (a NaN named in error_)
    return step;
  };
  constexpr Real inf = std::numeric_limits<Real>::infinity();
  std::fill(dt, dt + num_particles(), inf);
  slots_of(active, served_slots_);  // (a sink: below)
  const MinimumImage<D> image(ns_.box());
  active_steps_.clear();
  for (const std::size_t a : served_slots_) {
    // Both directions of the limiter over a's neighbours within reach (a branch-free distance
    // pass first): the least own step among them (least_neighbour_step's), its bound on each.
    const std::span<const std::uint32_t> near = neighbours_within_reach(a, image);
    const Real own_a = own(a), cap = kNeighbourStepFactor * own_a;
    Real least = std::numeric_limits<Real>::infinity();
    for (const std::size_t b : near) {
      least = std::min(least, own(b));
      Real& dt_b = dt[perm_[b]];
      dt_b = std::min(dt_b, cap);
    }
    active_steps_.push_back(std::min(own_a, kNeighbourStepFactor * least));
  }
  // The particles whose density this event solved (the active ones' neighbourhoods; with
  // SubsetDensity::Predicted the active ones only): their own steps are current, and bound them
  // too (a neighbour compressed, or heated, past its level).
  for (std::size_t b = 0; b < n_; ++b)
    if (solved_at_x_[b]) dt[perm_[b]] = std::min(dt[perm_[b]], own(b));
  if (!finite) return 1;
  Real shortest = inf;  // over the active gas: a sink takes the shortest gas step
  std::size_t next = 0;
  for (std::size_t i : active)
    if (i < n_) shortest = std::min(shortest, dt[i] = active_steps_[next++]);
  std::fill(dt + n_, dt + num_particles(), shortest);
  return 0;
}

#define SPHARK_SPMHD_SUBSETS(D, K)                                                                        \
  template void SpmhdScheme<D, K>::slots_of(std::span<const std::size_t>, std::vector<std::uint32_t>&);     \
  template int SpmhdScheme<D, K>::rhs_subset(Real, const Real*, std::span<const std::size_t>, Real*);   \
  template int SpmhdScheme<D, K>::particle_stable_dt(Real, const Real*, const Real*, Real*);              \
  template int SpmhdScheme<D, K>::own_steps_by_slot(Real, const Real*, const Real*);                      \
  template Real SpmhdScheme<D, K>::least_neighbour_step(std::size_t, const MinimumImage<D>&) const;      \
  template std::span<const std::uint32_t> SpmhdScheme<D, K>::neighbours_within_reach(std::size_t, const MinimumImage<D>&); \
  template int SpmhdScheme<D, K>::active_stable_dt(Real, const Real*, const Real*, std::span<const std::size_t>, Real*);
#define SPHARK_SPMHD_SUBSETS_2D_3D(K) SPHARK_SPMHD_SUBSETS(2, K<2>) SPHARK_SPMHD_SUBSETS(3, K<3>)
SPHARK_KERNELS(SPHARK_SPMHD_SUBSETS_2D_3D)
#undef SPHARK_SPMHD_SUBSETS_2D_3D
#undef SPHARK_SPMHD_SUBSETS

}  // namespace sphark
