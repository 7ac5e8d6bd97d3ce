// The cleaning speed c_h of each particle (seed 000, eqs. (22)-(23): one global c_h; with
// SpmhdOptions::local_ch each particle's own, the state holding psi/c_h, Tricco, Price & Bate
// 2016), and its spread over SpmhdOptions::ch_spread kernel supports.
#include <algorithm>
#include <cstdint>
#include <limits>

#include "sphark/kernels/kernel_list.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"

namespace sphark {

// c_h of slots [begin, end): the global one, or each particle's own (local_ch).
template <int D, class K>
void SpmhdScheme<D, K>::set_cleaning_speeds(std::size_t begin, std::size_t end) {
  for (std::size_t a = begin; a < end; ++a)
    cleaning_speeds_[a] =
        opt_.local_ch ? opt_.overclean * (opt_.fixed_ch > 0 ? opt_.fixed_ch : fast_speed_[a]) : cleaning_speed_;
}

// c_h,a <- the largest c_h,b within ch_spread supports of a: ch_spread passes of
// c_a <- max(c_a, max_b c_b) over the pairs |x_ab| < support max(h_a, h_b).
// Where the values are read: every slot, or (rhs_subset, active_stable_dt) the served particles'
// slots and their list neighbours (R). Pass j writes the slots within ch_spread - j list hops
// of R, reading the slots one hop further: the values on R are those of a pass over all slots.
template <int D, class K>
void SpmhdScheme<D, K>::spread_cleaning_speeds() {
  const int passes = opt_.ch_spread;
  if (!opt_.local_ch || passes <= 0 || n_ == 0) return;
  const NeighbourList& L = ns_.list();
  const bool subset = !serve_particles_.empty() && serve_particles_.size() < n_;
  constexpr std::uint8_t far = std::numeric_limits<std::uint8_t>::max();
  spread_hops_.assign(n_, subset ? far : 0);
  if (subset) {
    slots_of(serve_particles_, served_slots_);
    for (const std::uint32_t a : served_slots_) spread_hops_[a] = 0;
    for (int hop = 0; hop < passes; ++hop)  // R: hop <= 1 (the served rows' neighbours); then further
      for (std::size_t a = 0; a < n_; ++a)
        if (spread_hops_[a] == hop)
          for (std::size_t k = L.begin(a); k < L.end(a); ++k) {
            std::uint8_t& h = spread_hops_[L.indices[k]];
            h = std::min<std::uint8_t>(h, static_cast<std::uint8_t>(hop + 1));
          }
  }
  const MinimumImage<D> image(ns_.box());
  const Real* x = x_.data();
  for (int pass = 1; pass <= passes; ++pass) {
    const int reach_hops = passes + 1 - pass;  // slots this pass writes: within reach_hops of the served
    spread_next_.assign(cleaning_speeds_.begin(), cleaning_speeds_.begin() + n_);
#pragma omp parallel for schedule(dynamic, 64)
    for (std::size_t a = 0; a < n_; ++a) {
      if (spread_hops_[a] > reach_hops) continue;
      Real c = cleaning_speeds_[a];
      for (std::size_t k = L.begin(a); k < L.end(a); ++k) {
        const std::size_t b = L.indices[k];
        if (!(cleaning_speeds_[b] > c)) continue;
        const Real reach = K::support * std::max(h_[a], h_[b]);
        if (image(x + D * a, x + D * b).squaredNorm() < reach * reach) c = cleaning_speeds_[b];
      }
      spread_next_[a] = c;
    }
    std::copy(spread_next_.begin(), spread_next_.end(), cleaning_speeds_.begin());
  }
}

#define SPHARK_SPMHD_CLEANING_SPEEDS(D, K)                                        \
  template void SpmhdScheme<D, K>::set_cleaning_speeds(std::size_t, std::size_t); \
  template void SpmhdScheme<D, K>::spread_cleaning_speeds();
#define SPHARK_SPMHD_CLEANING_SPEEDS_2D_3D(K) SPHARK_SPMHD_CLEANING_SPEEDS(2, K<2>) SPHARK_SPMHD_CLEANING_SPEEDS(3, K<3>)
SPHARK_KERNELS(SPHARK_SPMHD_CLEANING_SPEEDS_2D_3D)
#undef SPHARK_SPMHD_CLEANING_SPEEDS_2D_3D
#undef SPHARK_SPMHD_CLEANING_SPEEDS

}  // namespace sphark
