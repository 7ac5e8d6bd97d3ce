// The neighbour lists of SpmhdScheme: Verlet lists with per-particle radii (a skin mostly
// shared, SpmhdOptions::skin_own_fraction), cut at half a periodic box, and the slots renumbered
// in the lists' cell order after each build. When to rebuild: spmhd_density.cpp
// (ensure_neighbours_and_density).
#include <algorithm>
#include <numeric>
#include <limits>
#include <string>
#include <type_traits>

#include "sphark/core/profile.hpp"
#include "sphark/kernels/kernel_list.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"
#include "spmhd_halo.hpp"

namespace sphark {

// Half the shortest periodic side (+inf without one): the longest list radius the minimum image allows.
template <int D, class K>
Real SpmhdScheme<D, K>::half_period() const {
  Real half = std::numeric_limits<Real>::infinity();
  if (const auto& box = ns_.box())
    for (int k = 0; k < D; ++k)
      if (box->periodic[k]) half = std::min(half, 0.5 * (box->hi[k] - box->lo[k]));
  return half;
}

template <int D, class K>
int SpmhdScheme<D, K>::build_neighbours(const Real* x, bool grow_only) {
  Real h_min = std::numeric_limits<Real>::infinity();
  for (std::size_t i = 0; i < n_; ++i) {
    list_h_[i] = std::max(grow_only ? std::max(h_[i], list_h_[i]) : h_[i], list_h_needed_[i]);
    list_h_needed_[i] = 0;
    h_min = std::min(h_min, list_h_[i]);
  }
  // The minimum image needs 2 r <= the period: a skin is cut there (its list then serves less and
  // is rebuilt sooner), an h whose support reaches beyond has grown too far.
  const Real r_cap = half_period();
  const Real own = opt_.skin_own_fraction * opt_.skin, shared = n_ > 0 ? (opt_.skin - own) * h_min : 0;  // SpmhdOptions::skin_own_fraction
  Real support_max = 0;
  for (std::size_t i = 0; i < n_; ++i) {
    radii_[i] = std::min(K::support * (list_h_[i] * (1 + own) + shared), r_cap);
    support_max = std::max(support_max, K::support * list_h_[i]);
  }
  if (halo_)  // the halo's radii: their owners' of this build (spmhd_distributed.cpp)
    for (std::size_t s = n_; s < n_all_; ++s) radii_[s] = halo_->radius[perm_[s] - n_];
  Real r_max = 0;
  for (std::size_t i = 0; i < n_all_; ++i) r_max = std::max(r_max, radii_[i]);
  if (support_max > r_cap || r_max > r_cap) {  // (a halo radius, from its owner's build)
    error_ = "smoothing length grew beyond half the periodic box (support radius " +
             std::to_string(std::max(support_max, r_max)) + ", half the period " + std::to_string(r_cap) + ")";
    return 1;
  }
  if (n_all_ == 0) {  // a rank left without particles (distributed): nothing to list
    built_ = true;
    max_list_ = 0;
    return 0;
  }
  // rows sorted by particle index (serially), by global id (distributed); the halo's rows empty
  ns_.build(x, n_all_, r_max, slot_keys(), radii_.data(), n_);
  built_ = true;
  ++builds_;
  run_profile().tally(Tally::ListBuilds, 1);
  const NeighbourList& L = ns_.list();
  std::size_t longest = 0;
  for (std::size_t i = 0; i < n_; ++i) longest = std::max(longest, L.count(i));
  max_list_ = longest;
  sort_slots_by_cell();
  return 0;
}

// Whether the lists of the last build still hold every pair that can interact at x, and the
// largest h each list serves (list_h_served_). A pair is listed when it was closer than the larger
// of its two radii at the build, so an unlisted pair (i, j) is now at least
// max(R_i, R_j) - d_i - d_j apart (d: the displacements since the build), and list i serves
// h_i <= (R_i - d_i - d_max) / support, d_max the largest displacement. When that fails, the
// particles that moved most (F: the fewest of 4, 8, .. kFastMovers that works) are set apart:
// with delta the largest displacement outside F, list i serves h_i <= (R_i - d_i - delta) /
// support against the particles outside F, and the pairs of each fast particle j are checked one by
// one (fast_movers_listed; the rows are symmetric, so j's row says whether a pair is listed).
// So a few particles flung through the others (the collapse's control: lists rebuilt every ten
// evaluations, 54 % of its time, for particles whose own lists still served them) no longer make
// every list be rebuilt.
template <int D, class K>
bool SpmhdScheme<D, K>::lists_serve(const Real* x) {
  if (opt_.evolve_particles)
    ns_.displacements_since_build(x, displacement_);
  else
    displacement_.assign(n_, 0);
  const Real d_max = n_ > 0 ? *std::max_element(displacement_.begin(), displacement_.begin() + n_) : 0;
  if (serve_against(d_max, nullptr)) return true;
  if (n_ <= kFastMovers) return false;
  fast_movers_.resize(n_);
  std::iota(fast_movers_.begin(), fast_movers_.end(), 0u);
  const auto moved_more = [this](std::uint32_t a, std::uint32_t b) {
    return displacement_[a] > displacement_[b] || (displacement_[a] == displacement_[b] && a < b);
  };
  std::partial_sort(fast_movers_.begin(), fast_movers_.begin() + kFastMovers + 1, fast_movers_.end(), moved_more);
  is_fast_mover_.assign(n_, 0);
  // the fewest fast movers that let the others' lists serve (each checked pair by pair costs O(N))
  for (std::size_t f = 4, set = 0; f <= kFastMovers; f *= 2) {
    for (; set < f; ++set) is_fast_mover_[fast_movers_[set]] = 1;
    if (!serve_against(displacement_[fast_movers_[f]], is_fast_mover_.data())) continue;
    fast_movers_.resize(f);
    return fast_movers_listed(x);
  }
  return false;
}

// list_h_served_[i] = (R_i - d_i - partner) / support; a fast mover's R_i / support (its pairs'
// check lowers it to what its row serves); whether every h_i is within.
template <int D, class K>
bool SpmhdScheme<D, K>::serve_against(Real partner, const std::uint8_t* fast) {
  std::size_t short_lists = 0;
#pragma omp parallel for schedule(static) reduction(+ : short_lists)
  for (std::size_t i = 0; i < n_; ++i) {
    const Real served = (radii_[i] - displacement_[i] - partner) / K::support;
    list_h_served_[i] = fast && fast[i] ? std::max(h_[i], radii_[i] / K::support) : served;
    short_lists += h_[i] > list_h_served_[i];
  }
  return short_lists == 0;
}

// The pairs of each fast mover j not in its row: none may be within support max(h_j, h_b) (the
// guesses); one within support max(served_j, served_b) but beyond that lowers both served h to
// |x_jb| / support (still at least their h: a solve that needs more reports it and rebuilds).
template <int D, class K>
bool SpmhdScheme<D, K>::fast_movers_listed(const Real* x) {
  const NeighbourList& L = ns_.list();
  const MinimumImage<D> image(ns_.box());
  Real* served = list_h_served_.data();
  in_row_.assign(n_, 0);
  for (std::uint32_t j : fast_movers_) {
    for (std::size_t k = L.begin(j); k < L.end(j); ++k) in_row_[L.indices[k]] = 1;
    std::size_t missing = 0;
    Real served_j = served[j];
#pragma omp parallel for schedule(static) reduction(+ : missing) reduction(min : served_j)
    for (std::size_t b = 0; b < n_; ++b) {
      if (b == j || in_row_[b]) continue;
      const Real r2 = image(x + D * j, x + D * b).squaredNorm();
      const Real reach = K::support * std::max(served[j], served[b]);
      if (!(r2 < reach * reach)) continue;
      const Real r = std::sqrt(r2), interacting = K::support * std::max(h_[j], h_[b]);
      missing += r < interacting;
      served[b] = std::min(served[b], r / K::support);
      served_j = std::min(served_j, r / K::support);
    }
    if (missing > 0) return false;
    served[j] = served_j;
    for (std::size_t k = L.begin(j); k < L.end(j); ++k) in_row_[L.indices[k]] = 0;
  }
  return true;
}

// Renumbers the slots in the cell order of the fresh lists; the per-slot data that outlives this
// RHS (positions, h and its guesses, masses, the slot -> particle map) follows.
template <int D, class K>
void SpmhdScheme<D, K>::sort_slots_by_cell() {
  order_ = ns_.cell_order();
  if (halo_)  // this rank's particles first (their rows), then the halo, each in cell order
    std::stable_partition(order_.begin(), order_.end(), [this](std::uint32_t s) { return s < n_; });
  ns_.renumber(order_);
  // arrays of every slot (n_all_ entries) or of this rank's particles (n_: order_ starts with them)
  auto permute = [&](auto& v, int comps) {
    using T = typename std::decay_t<decltype(v)>::value_type;
    const std::size_t count = v.size() / comps;
    if (v.size() % comps != 0 || (count != n_ && count != n_all_)) return;
    permute_scratch_.resize(v.size());
    for (std::size_t i = 0; i < count; ++i)
      for (int k = 0; k < comps; ++k) permute_scratch_[comps * i + k] = static_cast<Real>(v[comps * order_[i] + k]);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = static_cast<T>(permute_scratch_[i]);
  };
  permute(x_, D);
  permute(h_, 1);
  permute(h_guess_, 1);
  permute(h_eval_, 1);
  permute(ms_, 1);
  permute(list_h_, 1);
  permute(radii_, 1);
  permute(divv_, 1);
  permute(t_h_slot_, 1);
  permute(zeta_over_omega_, 1);
  permute(solved_at_x_, 1);
  // solved before the build: after a migration (distributed), or the slots a subset evaluation
  // does not solve (serially): they follow their particles
  permute(rho_, 1);
  permute(omega_, 1);
  permute(perm_, 1);  // slot indices < 2^31: exact through a double
  if (halo_) permute(key_, 1);  // global ids < 2^32: exact too
}

#define SPHARK_SPMHD_LISTS(D, K)                                         \
  template Real SpmhdScheme<D, K>::half_period() const;                  \
  template int SpmhdScheme<D, K>::build_neighbours(const Real*, bool);   \
  template bool SpmhdScheme<D, K>::lists_serve(const Real*);             \
  template bool SpmhdScheme<D, K>::serve_against(Real, const std::uint8_t*); \
  template bool SpmhdScheme<D, K>::fast_movers_listed(const Real*);      \
  template void SpmhdScheme<D, K>::sort_slots_by_cell();
#define SPHARK_SPMHD_LISTS_2D_3D(K) SPHARK_SPMHD_LISTS(2, K<2>) SPHARK_SPMHD_LISTS(3, K<3>)
SPHARK_KERNELS(SPHARK_SPMHD_LISTS_2D_3D)
#undef SPHARK_SPMHD_LISTS_2D_3D
#undef SPHARK_SPMHD_LISTS

}  // namespace sphark
