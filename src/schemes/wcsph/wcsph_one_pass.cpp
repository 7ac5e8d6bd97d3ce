// WcsphSystem's serial RHS after the records in one pass over the slots (issue #19): each row's
// neighbours inside the support, its density gradient (delta-SPH with Antuono's correction), and
// the force rows as soon as the gradients of all their neighbours are in the records. A row's
// neighbours sit within about one cell row of slots (cell order), so its force row follows its
// gradient by that much, while the neighbours' records and the row's inside list are still in
// the second-level cache (the records at the leading edge prefetched: core/cache_hints.hpp); three
// passes over 10^6 particles read both back from memory. Every row sums exactly as in the separate
// passes (prepare_rows, forces; the distributed RHS's): results are equal bit for bit. The spans
// are the list rows' (skin included): a force row may wait a little longer than it must.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "sphark/core/cache_hints.hpp"
#include "sphark/core/profile.hpp"
#include "sphark/kernels/kernel_list.hpp"
#include "sphark/schemes/wcsph/wcsph_system.hpp"
#include "wcsph_halo.hpp"
#include "wcsph_rows_in_use.hpp"

namespace sphark {

template <int D, class Kernel>
void WcsphSystem<D, Kernel>::rows_in_one_pass(const Real* y, Real* ydot) {
  using wcsph_detail::Record;
  const std::size_t n = layout_.particles(), count = slot_particle_.size();
  const wcsph_detail::RowInput<D> in = row_input();
  const wcsph_detail::Rows<D, Kernel> rows = wcsph_detail::rows_in_use<D, Kernel>();
  const wcsph_detail::ForceStore<D> store = force_store(y, ydot);
  const bool gradient = corrected_diffusion();
  const std::uint32_t* particle = slot_particle_.data();
  reserve_inside_rows();
  const std::vector<RowSpan>& span = search_.row_spans();  // slots a row reads
  ScopedPhase timer(Phase::Forces);
  Real max_acc2 = 0;
#pragma omp parallel reduction(max : max_acc2)
  {
    const auto t = static_cast<std::size_t>(omp_get_thread_num()), nt = static_cast<std::size_t>(omp_get_num_threads());
    const std::size_t first = n * t / nt, last = n * (t + 1) / nt;  // this thread's slots
    auto force = [&](std::size_t a) { max_acc2 = std::max(max_acc2, store(particle[a], rows.forces(in, a, inside_row(a)))); };
    std::vector<std::uint32_t> deferred;  // rows reading another thread's slots: after the barrier
    // Row r's force row, once the gradients of slots first .. done are in: now, or deferred, or
    // not yet (false).
    auto settle = [&](std::size_t r, std::size_t done) {
      const auto [lo, hi] = span[r];
      if (lo < first || hi >= last)
        deferred.push_back(static_cast<std::uint32_t>(r));
      else if (hi <= done)
        force(r);
      else
        return false;
      return true;
    };
    std::size_t next = first;  // the first row whose force row waits
    for (std::size_t a = first; a < last; ++a) {
      prefetch_lines(in.record(std::min(span[a].second + kPrefetchSlotsAhead, count - 1)), sizeof(Real) * Record<D>::size);
      inside_count_[a] = rows.inside(in, a, inside_start(a));
      if (!gradient) {
        force(a);
        continue;
      }
      grad_rho_[a] = wcsph_detail::gradient_into_record(rows, in, a, inside_row(a), records_.data());
      while (next <= a && settle(next, a)) ++next;
    }
    while (gradient && next < last && settle(next, last - 1)) ++next;
#pragma omp barrier
    for (const std::uint32_t a : deferred) force(a);
  }
  max_accel_ = std::sqrt(max_acc2);
}

#define SPHARK_WCSPH_ONE_PASS(K)                                                   \
  template void WcsphSystem<2, K<2>>::rows_in_one_pass(const Real*, Real*); \
  template void WcsphSystem<3, K<3>>::rows_in_one_pass(const Real*, Real*);
SPHARK_KERNELS(SPHARK_WCSPH_ONE_PASS)
#undef SPHARK_WCSPH_ONE_PASS

}  // namespace sphark
