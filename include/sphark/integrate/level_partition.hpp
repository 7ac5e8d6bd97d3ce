#pragma once
// Particles binned by their own stable step into power-of-two levels (issue #17; the block
// steps of Phantom, Price et al. 2018 PASA 35 e031, §2.3.4, and the slow/fast split of MRIStep).
// Level l steps by dt_top / 2^l (or dt_top / ratio^l: the fixed-step levels of nested MRIStep);
// a particle with stable step dt (already scaled by the CFL safety factor) needs the smallest l
// with dt_top / 2^l <= dt (clamped to max_level).
// Hysteresis: a particle moves to a deeper level (shorter step) at once, but back to a
// shallower one only when its stable step exceeds that level's step by the factor
// (1 + hysteresis), so particles near a bin edge do not flip every step.
#include <cstddef>
#include <span>
#include <vector>

#include "sphark/core/types.hpp"

namespace sphark {

class LevelPartition {
 public:
  // Throws std::invalid_argument (one line) for dt_top <= 0, max_level < 0, hysteresis < 0,
  // ratio < 2.
  LevelPartition(Real dt_top, int max_level, Real hysteresis, int ratio = 2);

  // The level each particle needs for its stable step dt[i] (> 0, +inf allowed), without
  // hysteresis; throws std::invalid_argument for a non-positive or NaN step.
  int needed_level(Real dt) const;
  // The level of a particle now at level `current` whose stable step is dt: deeper at once,
  // shallower only with the margin (1 + hysteresis) (the rule update() applies to each).
  int next_level(int current, Real dt) const;
  // Bins the particles by their stable steps (dt.size() particles; a change of the particle
  // count starts afresh, without hysteresis). Returns true if any particle's level changed.
  bool update(std::span<const Real> dt);

  // Restores the levels of a previous partition (a restart: Stepper::resume_data); throws
  // std::invalid_argument for a level outside 0..max_level.
  void set_levels(std::vector<int> levels);

  int level(std::size_t i) const { return levels_[i]; }
  const std::vector<int>& levels() const { return levels_; }
  std::size_t size() const { return levels_.size(); }
  int deepest() const;  // the deepest occupied level (0 when empty)
  Real dt_top() const { return dt_top_; }
  Real level_dt(int l) const;  // dt_top / ratio^l
  // The particles (ascending) at level l, at levels >= l, at levels < l.
  std::vector<std::size_t> at(int l) const;
  std::vector<std::size_t> at_least(int l) const;
  std::vector<std::size_t> below(int l) const;

 private:
  Real dt_top_;
  int max_level_;
  Real hysteresis_;
  int ratio_;
  std::vector<int> levels_;
};

}  // namespace sphark
