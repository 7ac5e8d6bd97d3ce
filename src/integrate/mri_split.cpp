// The levels of the MRIStep stepper (mri_split.hpp).
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
      levels_(adaptive_ ? o.max_dt : o.fixed_dt, adaptive_ ? kMaxLevel : o.mri_levels - 1, o.partition_hysteresis,
              adaptive_ ? 2 : std::max(2, o.mri_ratio)),
      bound_(static_cast<std::size_t>(o.mri_levels), 0),
      h_(static_cast<std::size_t>(o.mri_levels)),
      sets_(static_cast<std::size_t>(o.mri_levels)) {
  if (o.mri_levels < 2) throw std::invalid_argument("mri_levels=" + std::to_string(o.mri_levels) + ": must be >= 2");
  if (!adaptive_)
    for (int k = 0; k < count(); ++k) h_[static_cast<std::size_t>(k)] = k == 0 ? o.fixed_dt : h_[k - 1] / o.mri_ratio;
  else
    set_adaptive_steps();  // (all on the top level until the first update)
}

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

// Adaptive: the power-of-two bounds of the MRI levels (mri_split.hpp).
void MriSplit::set_bounds(int l) {
  const int K = count(), span = std::max(0, levels_.deepest() - l);
  for (int k = 0; k < K; ++k) bound_[static_cast<std::size_t>(k)] = l + (k * span + K - 2) / (K - 1);  // l + ceil(k span / (K-1))
}

// Adaptive: level k's step, k < depth: T / 2^bound_k, at most h_0 / mri_ratio^(k / (depth-1)) (the
// deepest integrated level at least mri_ratio below the slow step); deeper levels as the deepest.
void MriSplit::set_adaptive_steps() {
  const int deepest = depth_ - 1;
  h_[0] = levels_.level_dt(bound_[0]);
  for (int k = 1; k < count(); ++k) {
    const auto ku = static_cast<std::size_t>(k);
    if (k > deepest) {
      h_[ku] = h_[ku - 1];
      continue;
    }
    const Real floor = k == deepest ? h_[0] / mri_ratio_ : h_[0] / std::pow(Real(mri_ratio_), Real(k) / deepest);
    h_[ku] = std::min(levels_.level_dt(bound_[ku]), floor);
  }
}

int MriSplit::level_of(std::size_t particle) const {
  const int l = levels_.level(particle);
  if (!adaptive_) return l;
  int k = 0;
  while (k + 1 < count() && l > bound_[static_cast<std::size_t>(k)]) ++k;
  return k;
}

void MriSplit::check_stable(std::span<const Real> stable, Real t) const {
  std::size_t worst = 0;
  for (std::size_t i = 1; i < stable.size(); ++i)
    if (stable[i] < stable[worst]) worst = i;
  if (stable.empty()) return;
  if (!adaptive_ && stable[worst] < h_fast())
    throw std::runtime_error("particle " + std::to_string(worst) + " has the stable step " + at_time(stable[worst]) +
                             " < the fastest step fixed_dt/mri_ratio^" + std::to_string(count() - 1) + "=" +
                             at_time(h_fast()) + " at t=" + at_time(t) + ": raise mri_ratio or mri_levels");
  if (adaptive_ && stable[worst] < levels_.level_dt(kMaxLevel))
    throw std::runtime_error("particle " + std::to_string(worst) + " has the stable step " + at_time(stable[worst]) +
                             " < max_dt/2^" + std::to_string(kMaxLevel) + " at t=" + at_time(t));
}

bool MriSplit::update(std::span<const Real> stable, Real t) {
  const bool levels_changed = levels_.update(stable);
  check_stable(stable, t);
  const std::vector<int> old_bounds = bound_;
  if (adaptive_) set_bounds(slow_level());
  if (built_ && !levels_changed && bound_ == old_bounds) return false;
  built_ = true;
  for (auto& s : sets_) s.clear();
  for (std::size_t i = 0; i < levels_.size(); ++i) sets_[static_cast<std::size_t>(level_of(i))].push_back(i);
  depth_ = 2;
  for (int k = 2; k < count(); ++k)
    if (!sets_[static_cast<std::size_t>(k)].empty()) depth_ = k + 1;
  if (adaptive_) set_adaptive_steps();
  return true;
}

}  // namespace sphark::detail
