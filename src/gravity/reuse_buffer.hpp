#pragma once
// resize() that reports whether the vector had to allocate (for the allocation counters).
#include <cstddef>

namespace sphark::gravity_detail {

template <class V>
inline bool resize_reporting_growth(V& v, std::size_t n) {
  const bool grows = n > v.capacity();
  v.resize(n);
  return grows;
}

}  // namespace sphark::gravity_detail
