// Power-of-two levels of the particles' stable steps, with hysteresis (level_partition.hpp).
#include "sphark/integrate/level_partition.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "number_text.hpp"

namespace sphark {

LevelPartition::LevelPartition(Real dt_top, int max_level, Real hysteresis, int ratio)
    : dt_top_(dt_top), max_level_(max_level), hysteresis_(hysteresis), ratio_(ratio) {
  if (!(dt_top > 0) || !std::isfinite(dt_top))
    throw std::invalid_argument("partition top step=" + detail::number_text(dt_top) + ": must be finite and > 0");
  if (max_level < 0 || max_level > 60)
    throw std::invalid_argument("partition max_level=" + std::to_string(max_level) + ": must be in 0..60");
  if (!(hysteresis >= 0)) throw std::invalid_argument("partition hysteresis=" + detail::number_text(hysteresis) + ": must be >= 0");
  if (ratio < 2) throw std::invalid_argument("partition ratio=" + std::to_string(ratio) + ": must be >= 2");
}

// dt_top / ratio^l: exact halvings for ratio 2, else l divisions.
Real LevelPartition::level_dt(int l) const {
  if (ratio_ == 2) return std::ldexp(dt_top_, -l);
  Real dt = dt_top_;
  for (int k = 0; k < l; ++k) dt /= ratio_;
  return dt;
}

// The smallest l with level_dt(l) <= dt (no log2 round-off at bin edges).
int LevelPartition::needed_level(Real dt) const {
  if (!(dt > 0)) throw std::invalid_argument("particle stable step=" + detail::number_text(dt) + ": must be > 0");
  int l = 0;
  while (l < max_level_ && level_dt(l) > dt) ++l;
  return l;
}

int LevelPartition::next_level(int current, Real dt) const {
  const int need = needed_level(dt);
  return need < current ? std::min(current, needed_level(dt / (1 + hysteresis_))) : need;
}

bool LevelPartition::update(std::span<const Real> dt) {
  const bool fresh = levels_.size() != dt.size();
  if (fresh) levels_.assign(dt.size(), 0);
  bool changed = fresh;
  for (std::size_t i = 0; i < dt.size(); ++i) {
    const int next = fresh ? needed_level(dt[i]) : next_level(levels_[i], dt[i]);
    changed = changed || next != levels_[i];
    levels_[i] = next;
  }
  return changed;
}

void LevelPartition::set_levels(std::vector<int> levels) {
  for (int l : levels)
    if (l < 0 || l > max_level_) throw std::invalid_argument("partition level=" + std::to_string(l) + ": outside 0.." + std::to_string(max_level_));
  levels_ = std::move(levels);
}

int LevelPartition::deepest() const {
  return levels_.empty() ? 0 : *std::max_element(levels_.begin(), levels_.end());
}

std::vector<std::size_t> LevelPartition::at(int l) const {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < levels_.size(); ++i)
    if (levels_[i] == l) out.push_back(i);
  return out;
}

std::vector<std::size_t> LevelPartition::at_least(int l) const {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < levels_.size(); ++i)
    if (levels_[i] >= l) out.push_back(i);
  return out;
}

std::vector<std::size_t> LevelPartition::below(int l) const {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < levels_.size(); ++i)
    if (levels_[i] < l) out.push_back(i);
  return out;
}

}  // namespace sphark
