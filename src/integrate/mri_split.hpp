#pragma once
// The partition of the particles into the levels of the MRIStep stepper (mri_stepper.cpp;
// issue #17): level 0 slow, level K-1 fastest, K = StepperOptions::mri_levels (two: slow/fast).
//
// Fixed slow step (StepperOptions::fixed_dt = h): level k steps by h / mri_ratio^k; a particle
// takes the shallowest level whose step is within its stable step (x cfl_safety), and one whose
// stable step is below the deepest level's step is an error.
// Adaptive slow step (fixed_dt = 0, max_dt = T): the particles are binned on the power-of-two
// levels of T (LevelPartition, hysteresis); the slow level l* is the shallowest level holding,
// with all shallower ones, at least mri_slow_fraction of the particles, d the deepest occupied.
// MRI level k >= 1 holds the power-of-two levels up to b_k = l* + ceil(k (d - l*) / (K - 1))
// (level K-1 up to d); with D the deepest MRI level holding a particle (at least 1), level k <= D
// steps by min(T / 2^b_k, h / mri_ratio^(k/D)), h = T / 2^l* the slow step: every particle steps
// within its stable step, the deepest at least mri_ratio times faster than the slow one. Deeper
// levels are empty (the stepper builds no integrator for them). With K = 2: fast h / max(mri_ratio,
// 2^(d - l*)).
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "sphark/integrate/level_partition.hpp"
#include "sphark/integrate/stepper_options.hpp"

namespace sphark::detail {

class MriSplit {
 public:
  explicit MriSplit(const StepperOptions& o);

  // Bins the particles by their stable steps (x cfl_safety) at time t. Returns true if the sets
  // changed (or were not built yet). Throws std::runtime_error (one line) when a particle's
  // stable step is below the deepest level's step.
  bool update(std::span<const Real> stable, Real t);
  // Restores the levels of a previous run (resume_data).
  void set_levels(std::vector<int> levels) { levels_.set_levels(std::move(levels)); }
  const std::vector<int>& levels() const { return levels_.levels(); }

  int count() const { return static_cast<int>(sets_.size()); }                // K
  int depth() const { return depth_; }  // levels down to the deepest occupied one (at least 2)
  const std::vector<std::size_t>& set(int k) const { return sets_[static_cast<std::size_t>(k)]; }  // ascending
  int level_of(std::size_t particle) const;                                      // its MRI level
  Real h(int k) const { return h_[static_cast<std::size_t>(k)]; }               // level k's step
  Real h_slow() const { return h_.front(); }
  Real h_fast() const { return h_.back(); }
  bool adaptive() const { return adaptive_; }

 private:
  int slow_level() const;
  void set_bounds(int slow_level);
  void set_adaptive_steps();
  void check_stable(std::span<const Real> stable, Real t) const;

  bool adaptive_;
  int mri_ratio_;
  Real slow_fraction_;
  LevelPartition levels_;
  // Adaptive: the deepest power-of-two level of each MRI level; fixed: MRI level = partition level.
  std::vector<int> bound_;
  std::vector<Real> h_;
  bool built_ = false;
  int depth_ = 2;
  std::vector<std::vector<std::size_t>> sets_;
};

}  // namespace sphark::detail
