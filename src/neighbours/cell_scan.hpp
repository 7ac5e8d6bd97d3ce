#pragma once
// The inner loop of the neighbour-list build (neighbour_search.cpp): the particles of one cell
// tested against particle i, the hits appended. The cell's particles are read from the build's
// cell-ordered copy of the positions (one contiguous array per axis, CellPoints), so that the
// distance test runs over consecutive memory in vector lanes: on the AVX2 path four candidates at
// a time, the hits' indices appended by one shuffle of the comparison's mask; on the baseline
// path the test of a chunk into flags (a loop the compiler vectorises), then a branch-free append.
//
// The same lists on every path: the squared distance is (dx dx + dy dy) + dz dz in that order,
// rounded per operation (the vector paths are compiled without FMA, so nothing is contracted),
// and the test d2 < reach2 is exact: the baseline (SSE2) and AVX2 paths list the same pairs bit
// for bit (NeighbourSearch.ListsIndependentOfTheVectorPath).
#include <cstddef>
#include <cstdint>

#include "sphark/core/types.hpp"
#include "sphark/neighbours/neighbour_search.hpp"
#include "sphark/neighbours/periodic_box.hpp"

namespace sphark::neighbours_detail {

// The build's positions in cell order: x[k][s] is axis k of the particle in cell slot s;
// r2[s] its squared radius (null: one radius for all); particle[s] its index.
template <int D>
struct CellPoints {
  const Real* x[D];
  const Real* r2;
  const std::uint32_t* particle;
};

// Particle i at xi (squared radius r2_i, or the common r2max when cells.r2 is null) against
// slots [s0, s1): appends to out the particles j != i with |x_i - x_j|^2 < max(r2_i, r2_j)
// (minimum image along periodic axes), in slot order; returns the new end of out.
// (ScanCell<D>, declared with NeighbourSearch: a pointer to such a function.)

// The widest path this CPU has (AVX2 where present, else the x86-64 baseline); SPHARK_SIMD=
// scalar|sse2 (simd/dispatch.hpp) selects the baseline.
template <int D>
ScanCell<D> scan_cell_for_this_cpu();

}  // namespace sphark::neighbours_detail
