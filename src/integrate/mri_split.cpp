// The slow/fast split of the MRIStep stepper (mri_split.hpp).
#include "mri_split.hpp"
#include "number_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace sphark::detail {
namespace {

constexpr int kMaxLevel = 30;

}  // namespace

MriSplit::MriSplit(const StepperOptions& o)
    : adaptive_(!(o.fixed_dt > 0)),
      mri_ratio_(o.mri_ratio),
      slow_fraction_(o.mri_slow_fraction),
      levels_(adaptive_ ? o.max_dt : o.fixed_dt, adaptive_ ? kMaxLevel : 1, o.partition_hysteresis),
      h_slow_(levels_.dt_top()),
      ratio_(o.mri_ratio) {}

// The shallowest level l with at least slow_fraction of the particles on levels <= l.
int MriSplit::slow_level() const {
  if (!adaptive_) return 0;
  std::vector<std::size_t> count(kMaxLevel + 1, 0);
  for (int l : levels_.levels()) ++count[l];
  const auto need = static_cast<std::size_t>(std::ceil(slow_fraction_ * static_cast<Real>(levels_.size())));
  std::size_t below = 0;
  for (int l = 0; l <= kMaxLevel; ++l)
    if ((below += count[l]) >= need) return l;
  return kMaxLevel;
}

bool MriSplit::update(std::span<const Real> stable, Real t) {
  const bool levels_changed = levels_.update(stable);
  const int l = slow_level();
  if (!adaptive_) {
    std::size_t worst = 0;
    for (std::size_t i = 1; i < stable.size(); ++i)
      if (stable[i] < stable[worst]) worst = i;
    if (!stable.empty() && stable[worst] < h_fast())
      throw std::runtime_error("particle " + std::to_string(worst) + " has the stable step " + at_time(stable[worst]) +
                               " < fast step fixed_dt/mri_ratio=" + at_time(h_fast()) + " at t=" + at_time(t) +
                               ": raise mri_ratio");
  }
  if (adaptive_) {
    const Real deepest_dt = levels_.level_dt(levels_.deepest());
    for (std::size_t i = 0; i < stable.size(); ++i)
      if (stable[i] < deepest_dt)
        throw std::runtime_error("particle " + std::to_string(i) + " has the stable step " + at_time(stable[i]) +
                                 " < max_dt/2^" + std::to_string(kMaxLevel) + " at t=" + at_time(t));
  }
  if (built_ && !levels_changed && l == slow_level_) return false;
  built_ = true;
  slow_level_ = l;
  h_slow_ = levels_.level_dt(l);
  if (adaptive_) ratio_ = std::max(mri_ratio_, 1 << std::min(30, std::max(0, levels_.deepest() - l)));
  slow_.clear(), fast_.clear();
  for (std::size_t i = 0; i < levels_.size(); ++i) (levels_.level(i) > l ? fast_ : slow_).push_back(i);
  return true;
}

}  // namespace sphark::detail
