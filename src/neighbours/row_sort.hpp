#pragma once
// A neighbour row's indices in ascending order, or ascending in key[index] (the keys distinct):
// the rows' fixed summation order (neighbour_search.hpp). With Highway's vectorised quicksort
// (hwy/contrib/sort, run-time dispatch to the CPU's widest vectors): rows of ~100 indices sort
// 3-5x faster than with std::sort, whose comparisons mispredict (bench_neighbours, docs/performance.md).
#include <cstdint>

namespace sphark::neighbours_detail {

void sort_row(std::uint32_t* begin, std::uint32_t* end, const std::uint32_t* key);

}  // namespace sphark::neighbours_detail
