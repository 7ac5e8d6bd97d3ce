#pragma once
// The particles of a state in spatial order, and how far a flow has moved the state from it.
// The pair loops visit particles in cell order; a state in that order is gathered and scattered
// through memory in sequence, one whose particles a flow has scrambled at random (issue #19:
// 1.9 against 0.93 us per particle and RHS at 10^5). Both are functions of the positions
// alone (no neighbour lists, no counters), so a run that re-sorts when scrambled_fraction says so
// re-sorts at the same steps, in the same order, after a restart. Measured on Orszag-Tang 512 x 592 at t = 1
// (docs/performance.md): the state in cell order makes a step 14 % cheaper than in the lattice's
// row-by-row order, 25 % in the force pass (the rows sum in particle order, which then runs
// through memory).
#include <cstddef>
#include <optional>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/neighbours/periodic_box.hpp"

namespace sphark {

// The particles (indices into x, D values each) in row-major order of the cubic cells of side
// `cell` from the lower corner of their bounding box (of the box along its periodic axes, the
// positions wrapped into it), within a cell by index.
template <int D>
std::vector<std::size_t> cell_order(const Real* x, std::size_t n, Real cell, const std::optional<PeriodicBox<D>>& box);

// How far the state is from cell order (cells as cell_order's), in one pass over the positions:
// the cell changes between consecutive particles beyond the fewest possible (occupied cells - 1),
// per particle. 0 when each cell's particles are consecutive; a 2D lattice numbered row by row,
// against cells four rows and columns wide, enters each cell four times, four particles a time:
// 3/16. A flow raises it by 2 for each particle that leaves its run of a cell.
template <int D>
Real scrambled_fraction(const Real* x, std::size_t n, Real cell, const std::optional<PeriodicBox<D>>& box);

}  // namespace sphark
