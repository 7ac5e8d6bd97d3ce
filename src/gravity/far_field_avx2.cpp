// far_field_of_partners on four lanes for CPUs with AVX2 and FMA (far_field_sums.hpp): the
// template add_far_field (multipole.hpp) on __m256d, inlined into a function compiled for that
// target. A last group of fewer than four partners fills the free lanes with a massless source
// at unit distance (adds nothing). Lanes are filled with _mm256_set_pd (no stores and reloads). Only this file instantiates the __m256d formula.
#include "far_field_sums.hpp"

#if defined(SPHARK_GRAVITY_HAVE_AVX2)
#include <immintrin.h>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wignored-attributes"  // __m256d's may_alias: irrelevant to a member type
#pragma GCC diagnostic ignored "-Wpsabi"

namespace sphark::gravity_detail {

__attribute__((target("avx2,fma"), flatten)) LocalExpansion far_field_of_partners_avx2(
    const TreeNode& A, const std::vector<TreeNode>& nodes, const std::uint32_t* partner, std::uint32_t count) {
  LocalExpansionT<__m256d> L4;
  for (std::uint32_t k = 0; k < count; k += 4) {
    const std::uint32_t left = count - k;
    const TreeNode &B0 = nodes[partner[k]], &B1 = nodes[partner[left > 1 ? k + 1 : k]];
    const TreeNode &B2 = nodes[partner[left > 2 ? k + 2 : k]], &B3 = nodes[partner[left > 3 ? k + 3 : k]];
    const __m256d used = _mm256_castsi256_pd(first_lanes_mask(static_cast<long long>(left)));
    __m256d R[3], quad[6];
    for (int c = 0; c < 3; ++c)
      R[c] = _mm256_blendv_pd(_mm256_set1_pd(c == 0 ? 1.0 : 0.0),
                              _mm256_sub_pd(_mm256_set1_pd(A.com[c]), _mm256_set_pd(B3.com[c], B2.com[c], B1.com[c], B0.com[c])),
                              used);
    for (int c = 0; c < 6; ++c) quad[c] = _mm256_and_pd(used, _mm256_set_pd(B3.quad[c], B2.quad[c], B1.quad[c], B0.quad[c]));
    const __m256d mass = _mm256_and_pd(used, _mm256_set_pd(B3.mass, B2.mass, B1.mass, B0.mass));
    const __m256d r2 = _mm256_fmadd_pd(R[0], R[0], _mm256_fmadd_pd(R[1], R[1], _mm256_mul_pd(R[2], R[2])));
    const __m256d ir = _mm256_div_pd(_mm256_set1_pd(1), _mm256_sqrt_pd(r2));
    add_far_field(L4, R, ir, mass, quad);
  }
  LocalExpansion L;
  L.c0 = lane_sum(L4.c0);
  for (int c = 0; c < 3; ++c) L.c1[c] = lane_sum(L4.c1[c]);
  for (int c = 0; c < 6; ++c) L.c2[c] = lane_sum(L4.c2[c]);
  for (int c = 0; c < 10; ++c) L.c3[c] = lane_sum(L4.c3[c]);
  return L;
}

}  // namespace sphark::gravity_detail

#pragma GCC diagnostic pop
#endif
