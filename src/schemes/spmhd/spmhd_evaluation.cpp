// What the SPMHD scheme's last evaluations were (see spmhd_scheme.hpp): evaluate() for
// diagnostics and frames (nothing again at the same state), and whether the last evaluation was of
// every particle at given positions (the sink creation checks and the self-gravity reuse read it).
#include <algorithm>
#include <cstdint>

#include "sphark/integrate/callback_errors.hpp"
#include "sphark/kernels/kernel_list.hpp"
#include "sphark/schemes/spmhd/spmhd_scheme.hpp"
#include "spmhd_halo.hpp"

namespace sphark {

// Every particle was evaluated at y's positions (fully_evaluated_at_positions_of).
template <int D, class K>
void SpmhdScheme<D, K>::note_full_evaluation(const Real* y) {
  full_rhs_at_x_ = !halo_ && opt_.evolve_particles;
  const Real* xs = sinks() > 0 ? y + layout_.offset(Species::Sink, Field::Position) : nullptr;
  full_rhs_sink_x_.assign(xs, xs ? xs + 3 * sinks() : xs);
}

template <int D, class K>
bool SpmhdScheme<D, K>::fully_evaluated_at_positions_of(const Real* y) const {
  if (!full_rhs_at_x_ || x_.size() != D * n_ || full_rhs_sink_x_.size() != 3 * sinks()) return false;
  const Real* xs = sinks() > 0 ? y + layout_.offset(Species::Sink, Field::Position) : nullptr;
  if (xs && !std::equal(full_rhs_sink_x_.begin(), full_rhs_sink_x_.end(), xs)) return false;
  const Real* x = y + layout_.offset(Field::Position);
  for (std::size_t s = 0; s < n_; ++s)
    for (int k = 0; k < D; ++k)
      if (x[D * perm_[s] + k] != x_[D * s + k]) return false;
  return true;
}

template <int D, class K>
int SpmhdScheme<D, K>::evaluate(Real t, const Real* y) noexcept {
  const double pairs_before = pairs_total_;
  int rc = 0;
  try {  // diagnostics and frames: an exception becomes a failure code with its message
    // y evaluated last (no rhs() or prepare() since): every per-particle array is already y's
    // (distributed: on every rank, or every rank evaluates)
    bool same = evaluated_version_ == version_ && std::equal(y, y + layout_.size(), evaluated_y_.begin());
    if (halo_) same = halo_->comm().allreduce(std::int64_t(same ? 1 : 0), ReduceOp::Min) == 1;
    if (same) return 0;
    rc = rhs(t, y, scratch_.data());
  } catch (...) {
    error_ = current_exception_message("SpmhdScheme::evaluate");
    rc = -1;
  }
  if (rc == 0) {
    evaluated_y_.assign(y, y + layout_.size());
    evaluated_version_ = version_;
  }
  --rhs_calls_;  // diagnostics are not counted as integrator work
  pairs_total_ = pairs_before;
  return rc;
}

#define SPHARK_SPMHD_EVALUATION(D, K)                                              \
  template void SpmhdScheme<D, K>::note_full_evaluation(const Real*);               \
  template bool SpmhdScheme<D, K>::fully_evaluated_at_positions_of(const Real*) const; \
  template int SpmhdScheme<D, K>::evaluate(Real, const Real*) noexcept;
#define SPHARK_SPMHD_EVALUATION_2D_3D(K) SPHARK_SPMHD_EVALUATION(2, K<2>) SPHARK_SPMHD_EVALUATION(3, K<3>)
SPHARK_KERNELS(SPHARK_SPMHD_EVALUATION_2D_3D)
#undef SPHARK_SPMHD_EVALUATION_2D_3D
#undef SPHARK_SPMHD_EVALUATION

}  // namespace sphark
