#include "row_sort.hpp"

#include <hwy/contrib/sort/vqsort.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace sphark::neighbours_detail {

namespace {
// Below this length std::sort is faster: the vectorised sort costs ~0.3 us per call whatever the
// length up to ~60 (bench_neighbours: 2D rows of 26, 3D rows of 107).
constexpr std::size_t kVectorSortFrom = 48;
// One sorter and one key buffer per thread (the build's OpenMP threads), kept for later rows.
const hwy::Sorter& sorter() {
  thread_local const hwy::Sorter s;
  return s;
}
}  // namespace

void sort_row(std::uint32_t* begin, std::uint32_t* end, const std::uint32_t* key) {
  const auto n = static_cast<std::size_t>(end - begin);
  if (!key) {
    if (n < kVectorSortFrom) std::sort(begin, end);
    else sorter()(begin, n, hwy::SortAscending());
    return;
  }
  // (key << 32) | index: ascending in key, which is distinct per particle; the keys looked up
  // once, not at every comparison
  thread_local std::vector<std::uint64_t> keyed;
  if (keyed.size() < n) keyed.resize(2 * n);
  for (std::size_t k = 0; k < n; ++k) keyed[k] = std::uint64_t{key[begin[k]]} << 32 | begin[k];
  if (n < kVectorSortFrom) std::sort(keyed.data(), keyed.data() + n);
  else sorter()(keyed.data(), n, hwy::SortAscending());
  for (std::size_t k = 0; k < n; ++k) begin[k] = static_cast<std::uint32_t>(keyed[k]);
}

}  // namespace sphark::neighbours_detail
