#pragma once
// The particles' own stable steps on power-of-two levels (what a multirate or block-step
// integrator exploits; issues #16, #17): level k holds the particles with
//   2^k dt_min <= dt_a < 2^(k+1) dt_min,   dt_min = min_a dt_a,
// and `unlimited` those without a finite step. With each particle stepped at its level's step
// 2^k dt_min instead of the global dt_min, the particle evaluations per unit time fall by
//   speedup = N_finite / sum_k count_k 2^(-k)
// (block steps' ideal, before any overhead).
#include <cstddef>
#include <vector>

#include "sphark/core/types.hpp"

namespace sphark {

struct StepLevels {
  Real dt_min = 0;                 // +inf when no step is finite
  std::vector<std::size_t> count;  // per level, from 0
  std::size_t unlimited = 0;
  Real speedup() const;
};

// dt_a: one stable step per particle (+inf or NaN: unlimited).
StepLevels step_levels(const std::vector<Real>& dt);

}  // namespace sphark
