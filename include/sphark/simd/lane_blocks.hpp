#pragma once
// Blocks of W neighbour indices for the lane-generic pair rows (WCSPH and SPMHD): a row's entries
// taken W at a time, the last block padded with its last entry, and the mask of its valid lanes.
#include <cstddef>
#include <cstdint>

#include "sphark/simd/lanes.hpp"

namespace sphark::simd {

// The W entries of list from k on (of end), padded with the last: true for a full block.
template <int W>
inline bool block_of(const std::uint32_t* list, std::size_t k, std::size_t end, const std::uint32_t*& b,
                     std::uint32_t (&tail)[W]) {
  b = list + k;
  if (k + W <= end) return true;
  for (int l = 0; l < W; ++l) tail[l] = list[k + l < end ? k + l : end - 1];
  b = tail;
  return false;
}

// Lanes l < valid: true.
template <class S>
inline auto first_lanes(std::size_t valid) {
  return lane_numbers<S>() < broadcast<S>(static_cast<Real>(valid));
}

// The first 4 x Groups fields of the records of the W neighbours b (records of `stride` Reals),
// one lane per neighbour: what a pair row reads of its neighbours.
template <class S, int Groups>
struct GatheredFields {
  S f[4 * Groups];
  GatheredFields(const Real* records, int stride, const std::uint32_t* b) {
    for (int g = 0; g < Groups; ++g) {
      const Group<S> group = gather_group<S>(records, stride, b, 4 * g);
      for (int k = 0; k < 4; ++k) f[4 * g + k] = group.f[k];
    }
  }
  S operator[](int k) const { return f[k]; }
  template <int N>
  LaneVec<S, N> vec(int k) const {
    LaneVec<S, N> v;
    for (int i = 0; i < N; ++i) v[i] = f[k + i];
    return v;
  }
};

}  // namespace sphark::simd
