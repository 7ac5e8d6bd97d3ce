#pragma once
// Software prefetch of the records a pair loop is about to gather (issue #19). A row's neighbours
// lie within its span of slots (NeighbourSearch::row_spans); as the rows advance in cell order, the
// span's upper end reaches records last written long ago (at 10^6 particles, out of every cache):
// the loops fetch the record this many slots beyond it. A hint only: results do not change.
#include <cstddef>

namespace sphark {

inline constexpr std::size_t kPrefetchSlotsAhead = 32;

// Every cache line of bytes [p, p + bytes).
inline void prefetch_lines(const void* p, std::size_t bytes) {
  const char* c = static_cast<const char*>(p);
  for (std::size_t o = 0; o < bytes; o += 64) __builtin_prefetch(c + o);
  __builtin_prefetch(c + bytes - 1);
}

}  // namespace sphark
