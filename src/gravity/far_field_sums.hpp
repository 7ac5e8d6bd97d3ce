#pragma once
// A node's local expansion from its far partners (multipole.hpp, add_far_field): four partners
// at a time with AVX2 + FMA where the CPU has them (far_field_avx2.cpp, a short last group
// with massless lanes), else two at a time with SSE2 and an odd last one scalar (the same
// formula on every path). The order of the sums is fixed by the partner list alone (on a
// given path).
#include <cmath>
#include <cstdint>

#include "sphark/gravity/gravity_tree.hpp"
#include "simd_dispatch.hpp"
#include "sphark/gravity/multipole.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace sphark::gravity_detail {

#if defined(SPHARK_GRAVITY_HAVE_AVX2)
LocalExpansion far_field_of_partners_avx2(const TreeNode& A, const std::vector<TreeNode>& nodes,
                                          const std::uint32_t* partner, std::uint32_t count);
#endif

inline LocalExpansion far_field_of_partners(const TreeNode& A, const std::vector<TreeNode>& nodes,
                                            const std::uint32_t* partner, std::uint32_t count) {
#if defined(SPHARK_GRAVITY_HAVE_AVX2)
  if (cpu_has_avx2_fma()) return far_field_of_partners_avx2(A, nodes, partner, count);
#endif
  LocalExpansion L;
  std::uint32_t k = 0;
#if defined(__SSE2__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wignored-attributes"  // __m128d's may_alias: irrelevant to a member type
  LocalExpansionT<__m128d> L2;
#pragma GCC diagnostic pop
  for (; k + 2 <= count; k += 2) {
    const TreeNode &B0 = nodes[partner[k]], &B1 = nodes[partner[k + 1]];
    __m128d R[3], quad[6];
    for (int c = 0; c < 3; ++c) R[c] = _mm_set_pd(A.com[c] - B1.com[c], A.com[c] - B0.com[c]);
    for (int c = 0; c < 6; ++c) quad[c] = _mm_set_pd(B1.quad[c], B0.quad[c]);
    const __m128d ir = _mm_set1_pd(1) / _mm_sqrt_pd(R[0] * R[0] + R[1] * R[1] + R[2] * R[2]);
    add_far_field(L2, R, ir, _mm_set_pd(B1.mass, B0.mass), quad);
  }
  const auto lane_sum = [](__m128d v) {
    alignas(16) Real l[2];
    _mm_store_pd(l, v);
    return l[0] + l[1];
  };
  L.c0 = lane_sum(L2.c0);
  for (int c = 0; c < 3; ++c) L.c1[c] = lane_sum(L2.c1[c]);
  for (int c = 0; c < 6; ++c) L.c2[c] = lane_sum(L2.c2[c]);
  for (int c = 0; c < 10; ++c) L.c3[c] = lane_sum(L2.c3[c]);
#endif
  for (; k < count; ++k) {
    const TreeNode& B = nodes[partner[k]];
    const Real R[3] = {A.com[0] - B.com[0], A.com[1] - B.com[1], A.com[2] - B.com[2]};
    add_far_field(L, R, B.mass, B.quad);
  }
  return L;
}

}  // namespace sphark::gravity_detail
