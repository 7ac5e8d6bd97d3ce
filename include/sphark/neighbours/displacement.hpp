#pragma once
// The largest displacement of n particles from reference positions (minimum image when a box is
// given): the Verlet-skin validity check of the neighbour searches.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/neighbours/periodic_box.hpp"

namespace sphark {

// max_i |x_i - ref_i|, both D values per particle; OpenMP-parallel. With `order`, x_i is the
// position of particle order[i] of x (ref in another order than x, without a copy).
template <int D>
Real max_displacement(const Real* x, const Real* ref, std::size_t n, const std::optional<PeriodicBox<D>>& box,
                      const std::uint32_t* order = nullptr);

// out[i] = |x_i - ref_i| for each of the n particles (as max_displacement, order likewise).
template <int D>
void displacements(const Real* x, const Real* ref, std::size_t n, const std::optional<PeriodicBox<D>>& box,
                   std::vector<Real>& out, const std::uint32_t* order = nullptr);

}  // namespace sphark
