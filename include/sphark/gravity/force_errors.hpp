#pragma once
// How far one gravity solution is from a reference (tests and benchmarks): per-particle
// relative force errors and their quantiles.
#include <cstddef>
#include <vector>

#include "sphark/core/types.hpp"

namespace sphark {

// |a_test - a_ref| / |a_ref| per particle (accelerations 3 x n).
std::vector<Real> relative_force_errors(const Real* test, const Real* ref, std::size_t n);
// The p-quantile (0 <= p <= 1) by the nearest rank; v non-empty.
Real quantile(std::vector<Real> v, Real p);

}  // namespace sphark
