#pragma once
// The run-time choice of the tree's vector loops: on x86-64 with GCC, AVX2 + FMA versions
// (near_field_avx2.cpp, softened_avx2.cpp, far_field_avx2.cpp) are compiled with a target
// attribute and used when the CPU has them; else SSE2 (the x86-64 baseline) or scalar code.
#if defined(__GNUC__) && defined(__x86_64__)
#define SPHARK_GRAVITY_HAVE_AVX2 1
#endif

#if defined(SPHARK_GRAVITY_HAVE_AVX2)
#include <immintrin.h>

#include "sphark/core/types.hpp"

namespace sphark::gravity_detail {
// True if the AVX2 loops are in use: the CPU has AVX2 and FMA, and neither the environment
// (SPHARK_GRAVITY_SIMD=sse2, read once) nor use_avx2(false) turned them off.
bool cpu_has_avx2_fma();
bool use_avx2(bool on);  // returns whether they are on now

// All bits set in lanes 0 .. n-1 of four (n may exceed 4: all lanes), clear in the others.
__attribute__((target("avx2,fma"))) inline __m256i first_lanes_mask(long long n) {
  return _mm256_cmpgt_epi64(_mm256_set1_epi64x(n), _mm256_set_epi64x(3, 2, 1, 0));
}

// The sum of the four lanes (the AVX2 loops' final reductions).
__attribute__((target("avx2,fma"))) inline Real lane_sum(__m256d v) {
  const __m128d lo = _mm256_castpd256_pd128(v), hi = _mm256_extractf128_pd(v, 1), s = _mm_add_pd(lo, hi);
  return _mm_cvtsd_f64(_mm_add_sd(s, _mm_unpackhi_pd(s, s)));
}
}  // namespace sphark::gravity_detail
#endif
