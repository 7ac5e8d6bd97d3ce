#include "collective_system.hpp"

#include <cmath>
#include <limits>

#include "sphark/integrate/callback_errors.hpp"

namespace sphark::detail {

CollectiveSystem::CollectiveSystem(OdeSystem& inner, Communicator comm, std::vector<ReduceOp> root_reduction)
    : ForwardingSystem(inner), comm_(std::move(comm)), root_reduction_(std::move(root_reduction)) {
  root_reduction_.resize(static_cast<std::size_t>(std::max(0, inner_.num_roots())), ReduceOp::Min);
}

template <class F>
int CollectiveSystem::local_call(const char* what, F&& f) noexcept {
  local_error_.clear();
  try {
    const int code = f();
    if (code != 0) local_error_ = inner_.last_error();
    if (code != 0 && local_error_.empty()) local_error_ = std::string(what) + " returned " + std::to_string(code);
    return code;
  } catch (...) {
    local_error_ = current_exception_message(what);
    return -1;
  }
}

int CollectiveSystem::agreed(int code) {
  std::string message = local_error_;
  const int worst = comm_.agree(code, message);
  error_ = worst != 0 ? message : std::string();
  return worst;
}

int CollectiveSystem::rhs(Real t, const Real* y, Real* ydot) {
  return agreed(local_call("rhs", [&] { return inner_.rhs(t, y, ydot); }));
}

int CollectiveSystem::stiff_diagonal(Real t, const Real* y, Real* c) {
  return agreed(local_call("stiff_diagonal", [&] { return inner_.stiff_diagonal(t, y, c); }));
}

// min over the ranks; NaN if any rank's value is NaN; an exception on any rank is thrown on all.
Real CollectiveSystem::max_stable_dt(Real t, const Real* y, const Real* ydot) {
  Real local = 0;
  const int code = local_call("max_stable_dt", [&] {
    local = inner_.max_stable_dt(t, y, ydot);
    return 0;
  });
  double v[3] = {std::isnan(local) ? std::numeric_limits<double>::infinity() : local, std::isnan(local) ? -1.0 : 0.0,
                 code != 0 ? -1.0 : 0.0};
  comm_.allreduce(v, 3, ReduceOp::Min);
  if (v[2] < 0) throw CollectiveError(comm_.gather_messages(local_error_));
  return v[1] < 0 ? std::numeric_limits<Real>::quiet_NaN() : v[0];
}

// One Allreduce (min) of [g_k for Min, -g_k for Max, 0 for Sum, code, -code], a second (sum)
// only when some root is summed.
int CollectiveSystem::roots(Real t, const Real* y, Real* g) {
  const std::size_t k = root_reduction_.size();
  const int code = local_call("roots", [&] { return inner_.roots(t, y, g); });
  buffer_.assign(k + 2, 0.0);
  bool any_sum = false;
  for (std::size_t j = 0; j < k && code == 0; ++j) {
    if (root_reduction_[j] == ReduceOp::Min) buffer_[j] = g[j];
    if (root_reduction_[j] == ReduceOp::Max) buffer_[j] = -g[j];
  }
  buffer_[k] = code;
  buffer_[k + 1] = -code;
  comm_.allreduce(buffer_.data(), buffer_.size(), ReduceOp::Min);
  const int worst = buffer_[k] < 0 ? static_cast<int>(buffer_[k]) : static_cast<int>(-buffer_[k + 1]);
  if (worst != 0) {
    error_ = comm_.gather_messages(code != 0 ? local_error_ : std::string());
    return worst;
  }
  for (std::size_t j = 0; j < k; ++j) any_sum = any_sum || root_reduction_[j] == ReduceOp::Sum;
  std::vector<double> sums;
  if (any_sum) {
    sums.assign(k, 0.0);
    for (std::size_t j = 0; j < k; ++j)
      if (root_reduction_[j] == ReduceOp::Sum) sums[j] = g[j];
    comm_.allreduce(sums.data(), k, ReduceOp::Sum);
  }
  for (std::size_t j = 0; j < k; ++j) {
    if (root_reduction_[j] == ReduceOp::Min) g[j] = buffer_[j];
    if (root_reduction_[j] == ReduceOp::Max) g[j] = -buffer_[j];
    if (root_reduction_[j] == ReduceOp::Sum) g[j] = sums[j];
  }
  error_.clear();
  return 0;
}

}  // namespace sphark::detail
