#pragma once
// The slow/fast split of the MRIStep stepper (mri_stepper.cpp; issue #17). Private to
// src/integrate/.
//
// Fixed slow step (StepperOptions::fixed_dt = h): particles whose stable step (x cfl_safety) is
// below h are fast (levels 0 / 1 of a LevelPartition with top step h), the fast step is
// h / mri_ratio, and a fast particle whose stable step is below it is an error.
// Adaptive slow step (fixed_dt = 0, max_dt = T): the particles are binned on the power-of-two
// levels of T (LevelPartition, hysteresis); the slow level l* is the shallowest level holding,
// with all shallower ones, at least mri_slow_fraction of the particles; h = T / 2^l*, the fast
// particles are those deeper than l*, and the fast step is h / max(mri_ratio, 2^(deepest - l*))
// (every fast particle then steps within its stable step).
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
  // changed (or were not built yet). Throws std::runtime_error (one line) in the fixed mode when
  // a fast particle's stable step is below the fast step.
  bool update(std::span<const Real> stable, Real t);
  // Restores the levels of a previous run (resume_data).
  void set_levels(std::vector<int> levels) { levels_.set_levels(std::move(levels)); }
  const std::vector<int>& levels() const { return levels_.levels(); }

  const std::vector<std::size_t>& slow() const { return slow_; }
  const std::vector<std::size_t>& fast() const { return fast_; }
  bool is_fast(std::size_t particle) const { return levels_.level(particle) > slow_level_; }
  Real h_slow() const { return h_slow_; }
  Real h_fast() const { return h_slow_ / ratio_; }
  int ratio() const { return ratio_; }
  bool adaptive() const { return adaptive_; }

 private:
  int slow_level() const;

  bool adaptive_;
  int mri_ratio_;
  Real slow_fraction_;
  LevelPartition levels_;
  int slow_level_ = 0;
  Real h_slow_;
  int ratio_;
  bool built_ = false;
  std::vector<std::size_t> slow_, fast_;
};

}  // namespace sphark::detail
