#pragma once
// Contiguous ranges [begin, end) of state entries, and element-wise loops over them in parallel
// (the leapfrog's kicks and drifts: every entry outside the position block, etc.).
#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace sphark::detail {

using EntrySegment = std::pair<std::size_t, std::size_t>;  // [first, second)

// The entries of [0, n) outside every block, as ascending segments.
inline std::vector<EntrySegment> segments_outside(std::vector<EntrySegment> blocks, std::size_t n) {
  std::sort(blocks.begin(), blocks.end());
  std::vector<EntrySegment> out;
  std::size_t from = 0;
  for (const auto& [b, e] : blocks) {
    if (b > from) out.push_back({from, std::min(b, n)});
    from = std::max(from, e);
  }
  if (from < n) out.push_back({from, n});
  return out;
}

// f(k) for every k of the segments, k in parallel where a segment is long (element-wise: the same
// result on any thread count).
template <class F>
void for_each_entry(const std::vector<EntrySegment>& segments, F&& f) {
  constexpr std::size_t kParallelEntries = 16384;  // shorter segments: one thread (no fork cost)
  for (const auto& [b, e] : segments) {
#pragma omp parallel for schedule(static) if (e - b > kParallelEntries)
    for (std::size_t k = b; k < e; ++k) f(k);
  }
}

}  // namespace sphark::detail
