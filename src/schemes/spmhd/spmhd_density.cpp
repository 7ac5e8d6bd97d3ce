// The density / smoothing-length solve of SpmhdScheme (seed 000, eqs. (4)-(5); Omega as in
// sphark/operators/density_summation.hpp), and when the neighbour lists must be rebuilt (the
// build itself: spmhd_lists.cpp).
//
// Speed: each particle's Newton iteration needs the sums at several trial h. The candidate
// neighbours (r, m_b) are gathered ONCE per particle into a per-thread buffer, and every Newton
// step sums over that buffer with the unit-h kernel shape (one 1/h per step, no filter: the
// shape vanishes beyond the support), in lanes (spmhd_density_sums.hpp; the path of
// simd/dispatch.hpp). Against sphark::solve_density: round-off differences.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "sphark/core/profile.hpp"
#include "sphark/gravity/gravity_grad_h.hpp"
#include "sphark/kernels/kernel_list.hpp"
#include "sphark/operators/density_summation.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"
#include "sphark/simd/dispatch.hpp"
#include "spmhd_density_sums.hpp"
#include "spmhd_halo.hpp"

namespace sphark {


// The initial guesses of the solve at t: the last iterates h_eval_ (solved at t_h_; h_ is one
// Newton step past them) advanced by the continuity equation, dh/dt = -h/(D rho) drho/dt =
// h div v / D (seed 000, eqs. (5) and (25)), with the div v of the last force pass (predict_h),
// or as they are. The error of the guess falls from O(dt) to O(dt^2), and the Newton iteration
// converges in one step fewer. Only a guess: the roots do not depend on it beyond the solve's
// tolerance; the factor is clamped to [0.8, 1.25]. Starting from the iterates, not from h_, a
// restart (resume: the iterates) starts every solve where the uninterrupted run does.
// Each slot from its own solve's time (t_h_slot_: subset evaluations solve some slots only); a
// slot already solved at these positions keeps its h.
template <int D, class K>
void SpmhdScheme<D, K>::predict_smoothing_lengths(Real t) {
  if (t_h_slot_.size() != n_) t_h_slot_.assign(n_, t_h_);
  if (solved_at_x_.size() != n_) solved_at_x_.assign(n_, 0);
  const bool predict = opt_.predict_h && h_rate_known_ && opt_.evolve_particles;
  const Real cap = h_cap();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n_; ++i) {
    if (solved_at_x_[i]) continue;
    const Real dt_over_d = predict && t != t_h_slot_[i] ? (t - t_h_slot_[i]) / D : 0;
    h_[i] = dt_over_d != 0 ? h_eval_[i] * std::clamp(1 + dt_over_d * divv_[i], Real(0.8), Real(1.25)) : h_eval_[i];
    h_[i] = std::min(h_[i], cap);
  }
}

template <int D, class K>
void SpmhdScheme<D, K>::set_h_time(Real t) {
  t_h_ = t;
  t_h_slot_.assign(n_, t);
}

// SubsetDensity::Predicted: the slots not solved at x_ (the active rows' neighbours) take the
// density of their predicted h, rho = m (eta / h)^D (seed 000, eq. (5)); Omega and zeta stay
// their last solve's.
template <int D, class K>
void SpmhdScheme<D, K>::densities_of_predicted_h() {
  const Real eta_d = std::pow(opt_.eta, D);
  for (std::size_t a = 0; a < n_; ++a) {
    if (solved_at_x_[a]) continue;
    Real h_d = h_[a];
    for (int k = 1; k < D; ++k) h_d *= h_[a];
    rho_[a] = ms_[a] * eta_d / h_d;
  }
}

// The slots not yet solved at x_ among those prepare() serves: every slot, or (rhs_subset) the
// slots of serve_particles_ and (SubsetDensity::Solved) of their list neighbours, which their
// rows read (every slot while some has never been solved: its rho would enter P, the speeds and c_h).
template <int D, class K>
void SpmhdScheme<D, K>::slots_to_solve() {
  solve_slots_.clear();
  if (serve_particles_.empty() || serve_particles_.size() >= n_ || !every_slot_solved_) {
    for (std::size_t a = 0; a < n_; ++a)
      if (!solved_at_x_[a]) solve_slots_.push_back(static_cast<std::uint32_t>(a));
    return;
  }
  const NeighbourList& L = ns_.list();
  std::vector<char>& wanted = solve_wanted_;
  wanted.assign(n_, 0);
  const bool neighbours = opt_.subset_density == SubsetDensity::Solved;
  slots_of(serve_particles_, served_slots_);
  for (const std::size_t a : served_slots_) {
    wanted[a] = 1;
    if (neighbours)
      for (std::size_t k = L.begin(a); k < L.end(a); ++k) wanted[L.indices[k]] = 1;
  }
  for (std::size_t a = 0; a < n_; ++a)
    if (wanted[a] && !solved_at_x_[a]) solve_slots_.push_back(static_cast<std::uint32_t>(a));
}

// Verlet lists with per-particle radii R_i (spmhd_lists.cpp: support * [list_h_i (1 + f skin) +
// (1 - f) skin min list_h], cut at half a periodic box). A pair closer than
// support * h_i now was closer than support * h_i + d_i + d_j at the build (d: displacements
// since), so particle i's list serves every h_i <= cap_i = (R_i - d_i - d_max) / support; a pair
// of the force loop (closer than support * max(h_a, h_b)) is listed when both h are within their
// caps (with a few fast movers set apart and checked pair by pair: lists_serve). Rebuild when
// some h (the guess: the predicted h) exceeds its cap, or when the density solve reports an h beyond.
// A list too short for its h grows by 1.5x per attempt of one solve, by 4x from the fifth: a
// guess far from its root (a restart's h of a particle that has since crossed the box, a poor
// first guess) reaches it within the eight attempts (1.5^4 4^3 = 324x), the cap included.
template <int D, class K>
Real SpmhdScheme<D, K>::list_growth_for_attempt(int attempt) {
  return attempt < 4 ? 1.5 : 4.0;
}

// At the positions of the last ensure_neighbours_and_density, at its time and with its h rates:
// whether the slots the current call serves are all solved (nothing for another call to do).
template <int D, class K>
bool SpmhdScheme<D, K>::served_slots_solved_at(Real t) {
  if (!(t == t_ensured_) || h_rate_known_ != rate_known_at_ensure_) return false;
  slots_to_solve();
  return solve_slots_.empty();
}

template <int D, class K>
int SpmhdScheme<D, K>::ensure_neighbours_and_density(Real t, const Real* x) {
  if (h_unset_) first_smoothing_lengths(x, true);
  predict_smoothing_lengths(t);
  h_guess_.assign(h_.begin(), h_.end());  // every attempt starts from the same guesses
  for (int attempt = 0; attempt < 8; ++attempt) {
    if (attempt > 0) std::copy(h_guess_.begin(), h_guess_.end(), h_.begin());
    {
      ScopedPhase timer(Phase::Neighbours);
      const bool rebuild = !built_ || attempt > 0 || !lists_serve(x);  // spmhd_lists.cpp
      if (rebuild) {
        // a retry's lists only grow: the needs of every attempt so far are kept
        if (const int rc = build_neighbours(x, attempt > 0)) return rc;
        for (std::size_t i = 0; i < n_; ++i) list_h_served_[i] = radii_[i] / K::support;
      }
    }
    ScopedPhase timer(Phase::DensityH);
    list_growth_ = list_growth_for_attempt(attempt);
    slots_to_solve();  // (after a build: the new slots)
    const bool all = solve_slots_.size() == n_;
    const DensityStats st = solve_density(x, all ? nullptr : &solve_slots_);
    if (st.outside_list == 0) {
      if (all) set_h_time(t), every_slot_solved_ = true;
      density_solves_ += static_cast<long>(solve_slots_.size());
      run_profile().tally(Tally::DensitySolves, static_cast<long>(solve_slots_.size()));
      for (std::uint32_t a : solve_slots_) t_h_slot_[a] = t, solved_at_x_[a] = 1;
      if (!all && opt_.subset_density == SubsetDensity::Predicted) densities_of_predicted_h();
      if (st.not_converged == 0) return 0;
      error_ = "density: h iteration did not converge for " + std::to_string(st.not_converged) + " particle(s)";
      return 1;  // recoverable: a smaller step moves the particles less
    }
  }
  error_ = "density: smoothing lengths keep growing beyond the neighbour lists";
  return 1;
}

// Solves (4)-(5) for every particle (Newton-Raphson with a bisection fallback, as
// sphark::solve_density); h_ holds the initial guess (the previous h), list_h_served_ the largest h the
// lists can serve.
namespace {
// The h solve's first candidates: neighbours within reach of 1.03 x the guess (1.03^2 = 1.06 of
// the guess's circle in 2D; a list serves h up to (1 + skin) x its build's). Only speed depends
// on it: an iterate beyond gathers them all.
constexpr Real kGuessReach = 1.03;
}  // namespace

template <int D, class K>
typename SpmhdScheme<D, K>::DensityStats SpmhdScheme<D, K>::solve_density(const Real* x,
                                                                          const std::vector<std::uint32_t>* only) {
  const int threads = omp_get_max_threads();
  const int lanes = simd_lanes(pair_loop_simd());
  const std::size_t room = static_cast<std::size_t>(lanes) * (max_list_ + 1), stride = 2 * room;
  if (cand_.size() < stride * static_cast<std::size_t>(threads)) cand_.resize(stride * threads);
  const NeighbourList& L = ns_.list();
  const Real* m = ms_.data();
  const std::uint32_t* key = slot_keys();  // each neighbour's lane: by particle number (global id)
  const MinimumImage<D> image(ns_.box());
  const Real eta_d = std::pow(opt_.eta, D), tol = opt_.h_tolerance;
  using spmhd_detail::DensitySums;
  DensitySums (*sums)(const Real*, const Real*, std::size_t, Real, Real) = spmhd_detail::density_sums<Real, D, K>;
  if (pair_loop_simd() == PairLoopSimd::Avx512) sums = spmhd_detail::density_sums_avx512<D, K>;
  if (pair_loop_simd() == PairLoopSimd::Avx2) sums = spmhd_detail::density_sums_avx2<D, K>;
  if (pair_loop_simd() == PairLoopSimd::Sse2) sums = spmhd_detail::density_sums<simd::Real2, D, K>;
  std::size_t not_converged = 0, outside = 0, iterations = 0, capped = 0;
  Real h_max = 0;
  const std::size_t rows = only ? only->size() : n_;
  const bool with_zeta = opt_.self_gravity && D == 3;  // the grad-h term of the gravity (spmhd_gravity.cpp)
  const Real cap = h_cap();
#pragma omp parallel reduction(+ : not_converged, outside, iterations, capped) reduction(max : h_max)
  {
    Real* rc = cand_.data() + stride * static_cast<std::size_t>(omp_get_thread_num());
    Real* mc = rc + room;
#pragma omp for schedule(dynamic, 64)
    for (std::size_t r = 0; r < rows; ++r) {
      const std::size_t i = only ? (*only)[r] : r;
      const Real h_list = std::min(list_h_served_[i], cap);
      // Candidates: every listed neighbour that a trial h <= h_reach can reach, in list order,
      // neighbour j in lane (particle number of j) mod W: entry c W + l of lane l. Each lane's
      // sum then runs over the same neighbours in the same order whatever other candidates the
      // list holds (those add exact zeros): a reused list gives the h of a fresh one, bit for bit,
      // and so does any h_reach above the trial h. First h_reach = kGuessReach x the guess (the
      // Newton iterates stay near a predicted guess; the list reaches (1 + skin) h), all of
      // h_list when an iterate goes beyond.
      Real h_reach = 0;
      std::size_t nc = 0;
      auto gather = [&](Real reach) {
        h_reach = reach;
        const Real r2_max = (K::support * reach) * (K::support * reach);
        std::size_t count[8] = {};
        for (std::size_t k = L.begin(i); k < L.end(i); ++k) {
          const std::size_t j = L.indices[k];
          const Real r2 = image(x + D * i, x + D * j).squaredNorm();
          // without a branch (a third of the entries fall outside, unpredictably): every entry is
          // written at its lane's next place, which only a candidate keeps
          const std::size_t l = key[j] & (lanes - 1), c = count[l] * lanes + l;  // lanes: 1, 2, 4 or 8
          rc[c] = std::sqrt(r2);
          mc[c] = m[j];
          count[l] += r2 < r2_max;
        }
        const std::size_t blocks = *std::max_element(count, count + lanes);
        nc = blocks * lanes;
        for (int l = 0; l < lanes; ++l)
          for (std::size_t c = count[l]; c < blocks; ++c) rc[c * lanes + l] = mc[c * lanes + l] = 0;
      };
      gather(std::min(h_list, kGuessReach * h_[i]));
      // rho(h) and drho/dh at smoothing length hh, self term first (seed 000, eq. (4)), from the
      // unit-h shape: W = w1(q) / h^D and dW/dh = -(D W + r dW/dr) / h = -(D w1 + q^2 f1) / h^(D+1),
      // with w1 = K::unit_w(q), q^2 f1 = K::unit_q_dw(q), q = r / h (kernels.hpp). Beyond the
      // support w1 = f1 = 0.
      auto density_at = [&](Real hh, Real& rho, Real& drho_dh) {
        if (hh > h_reach) gather(h_list);
        const Real hinv = 1.0 / hh;
        const DensitySums s = sums(rc, mc, nc, hinv, m[i]);
        Real hd = 1;
        for (int k = 0; k < D; ++k) hd *= hinv;
        rho = s.s0 * hd;
        drho_dh = -s.s1 * hd * hinv;
      };
      const Real m_eta = m[i] * eta_d;
      // From h_[i]: after resume() the interrupted run's last iterate, whose sums and Newton step
      // are then that run's, bit for bit. The root is one Newton step past the last sums, rho
      // taken there to first order (SmoothingLengthIterate): no sum at the root itself.
      bool converged = false;
      const SmoothingLengthIterate it =
          solve_smoothing_length<D>(density_at, h_[i], h_list, m_eta, tol, converged, iterations);
      if (!converged) ++not_converged;
      const Real hh = it.h_next;
      h_eval_[i] = it.h;
      h_[i] = hh;
      rho_[i] = it.rho_next();
      omega_[i] = 1 + hh / (D * rho_[i]) * it.drho_dh;  // dh/drho = -h / (D rho)
      if (with_zeta) {  // from the same candidates (every one within reach of hh: zero beyond)
        if (hh > h_reach) gather(h_list);
        zeta_over_omega_[i] = gravitational_zeta_of(rc, mc, nc, lanes, m[i], hh, rho_[i]) / omega_[i];
      }
      if (root_beyond_list<D>(density_at, hh, h_list, m_eta, tol)) {
        if (h_list < cap) {
          ++outside;
          list_h_needed_[i] = std::min(list_growth_ * h_list, cap);
        } else {  // SpmhdOptions::h_max: the sum (4) at the cap, h independent of rho there
          ++capped;
          Real drho_dh = 0;
          density_at(cap, rho_[i], drho_dh);
          h_[i] = h_eval_[i] = cap;
          omega_[i] = 1;
          if (with_zeta) zeta_over_omega_[i] = 0;
        }
      }
      h_max = std::max(h_max, h_[i]);
    }
  }
  h_iterations_ += static_cast<double>(iterations);
  return {not_converged, outside, iterations, capped, h_max};
}

// zeta_a of the gravitational grad-h term (Price & Monaghan 2007, §3; gravity/gravity_grad_h.hpp)
// at the solved h_a and rho_a, over the density solve's candidates (r, m; padding m = 0), lane by
// lane as the density sums: candidates beyond the support add exact zeros, so the lists' reach
// does not change a bit of it.
template <int D, class K>
Real SpmhdScheme<D, K>::gravitational_zeta_of(const Real* r, const Real* m, std::size_t count, int lanes, Real m_a,
                                              Real h_a, Real rho_a) {
  if constexpr (D == 3) {
    Real sum = zeta_init<K>(m_a, h_a);
    for (int l = 0; l < lanes; ++l) {
      Real lane = 0;
      for (std::size_t c = static_cast<std::size_t>(l); c < count; c += static_cast<std::size_t>(lanes))
        lane += zeta_pair<K>(m[c], r[c], h_a);
      sum += lane;
    }
    return zeta_finish(sum, h_a, rho_a);
  }
  return 0;
}

namespace {
// SpmhdOptions::h_max = 0 in a periodic box: the support at most 1 / 1.5 of the half period, so
// that a list with a skin of 0.5 still fits the minimum image at the cap (a longer skin is cut
// there: spmhd_lists.cpp). A constant, not the skin: results do not depend on the skin.
constexpr Real kBoxCapReserve = 1.5;
}  // namespace

template <int D, class K>
Real SpmhdScheme<D, K>::h_cap() const {
  return opt_.h_max > 0 ? opt_.h_max : half_period() / (K::support * kBoxCapReserve);
}

template <int D, class K>
std::size_t SpmhdScheme<D, K>::smoothing_lengths_at_cap() const {
  const Real cap = h_cap();
  return static_cast<std::size_t>(std::count_if(h_eval_.begin(), h_eval_.begin() + n_, [cap](Real h) { return h >= cap; }));
}

// The first guess of h: eta (volume / N)^(1/D) from the bounding box of all positions.
template <int D, class K>
void SpmhdScheme<D, K>::first_smoothing_lengths(const Real* x, bool apply) {
  constexpr Real inf = std::numeric_limits<Real>::infinity();
  Real box[2 * D + 1];  // -lo, hi, count: one Allreduce (max) when distributed
  for (int k = 0; k < D; ++k) box[k] = box[D + k] = -inf;
  for (std::size_t i = 0; i < n_; ++i)
    for (int k = 0; k < D; ++k) {
      box[k] = std::max(box[k], -x[D * i + k]);
      box[D + k] = std::max(box[D + k], x[D * i + k]);
    }
  box[2 * D] = static_cast<Real>(n_);
  if (halo_) {
    halo_->comm().allreduce(box, 2 * D, ReduceOp::Max);
    box[2 * D] = halo_->comm().allreduce(box[2 * D], ReduceOp::Sum);
  }
  Real volume = 1;
  for (int k = 0; k < D; ++k) volume *= box[D + k] + box[k];
  if (!apply) return;
  std::fill(h_.begin(), h_.begin() + n_, opt_.eta * std::pow(volume / box[2 * D], 1.0 / D));
  std::copy(h_.begin(), h_.begin() + n_, h_eval_.begin());
  h_unset_ = false;
}

#define SPHARK_SPMHD_DENSITY(D, K)                                                              \
  template void SpmhdScheme<D, K>::first_smoothing_lengths(const Real*, bool);                  \
  template Real SpmhdScheme<D, K>::h_cap() const;                                               \
  template Real SpmhdScheme<D, K>::list_growth_for_attempt(int);                                \
  template std::size_t SpmhdScheme<D, K>::smoothing_lengths_at_cap() const;                     \
  template int SpmhdScheme<D, K>::ensure_neighbours_and_density(Real, const Real*); \
  template void SpmhdScheme<D, K>::predict_smoothing_lengths(Real);                  \
  template void SpmhdScheme<D, K>::set_h_time(Real);                                 \
  template Real SpmhdScheme<D, K>::gravitational_zeta_of(const Real*, const Real*, std::size_t, int, Real, Real, Real); \
  template void SpmhdScheme<D, K>::slots_to_solve();                                 \
  template bool SpmhdScheme<D, K>::served_slots_solved_at(Real);                     \
  template void SpmhdScheme<D, K>::densities_of_predicted_h();                                 \
  template SpmhdScheme<D, K>::DensityStats SpmhdScheme<D, K>::solve_density(const Real*,               \
                                                                            const std::vector<std::uint32_t>*);
#define SPHARK_SPMHD_DENSITY_2D_3D(K) SPHARK_SPMHD_DENSITY(2, K<2>) SPHARK_SPMHD_DENSITY(3, K<3>)
SPHARK_KERNELS(SPHARK_SPMHD_DENSITY_2D_3D)
#undef SPHARK_SPMHD_DENSITY_2D_3D
#undef SPHARK_SPMHD_DENSITY

}  // namespace sphark
