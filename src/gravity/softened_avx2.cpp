// add_softened_list for CPUs with AVX2 and FMA (chosen at run time, near_field_sums.hpp): the
// softened pair interaction (kernel_softening.hpp, one_side and softened_pair) for four listed
// neighbours at a time (gathered), the polynomial piece of each lane chosen by masks.
#include "near_field_sums.hpp"

#if defined(SPHARK_GRAVITY_HAVE_AVX2)
#include <immintrin.h>
// GCC 12 warns inside _mm256_i32gather_pd (an intrinsic's own undefined source operand).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include "sphark/kernels/kernels.hpp"
#include "gravity_kernels.hpp"

namespace sphark::gravity_detail {

namespace {

struct Pair4 {
  __m256d force_over_r, phi;
};

template <int N>
__attribute__((target("avx2,fma"))) inline __m256d horner4(const std::array<Real, softening_detail::kMaxTerms>& c,
                                                           __m256d q) {
  __m256d s = _mm256_set1_pd(c[N - 1]);
  for (int j = N - 2; j >= 0; --j) s = _mm256_fmadd_pd(s, q, _mm256_set1_pd(c[j]));
  return s;
}

// one_side on four lanes; r = 0 is fine (inv_r = 0 there; the A_k terms are masked out on the
// innermost piece).
template <class K>
__attribute__((target("avx2,fma"))) inline Pair4 one_side4(__m256d r, __m256d inv_r, __m256d h, __m256d h_inv) {
  using Table = softening_detail::SofteningTable<K>;
  const __m256d q = _mm256_mul_pd(r, h_inv), q2 = _mm256_mul_pd(q, q);
  __m256d f = _mm256_setzero_pd(), v = f, a = f, outer = f;
  for (int k = 0; k < Table::count; ++k) {
    const softening_detail::SofteningPiece& pc = Table::pieces[k];
    const __m256d fk = horner4<Table::n_terms>(pc.force.c, q);
    const __m256d vk = _mm256_fmadd_pd(q2, horner4<Table::n_terms>(pc.potential.c, q), _mm256_set1_pd(pc.pot_const));
    if (k == 0) {
      f = fk, v = vk, a = _mm256_set1_pd(pc.mass_const);
      continue;
    }
    const __m256d in = _mm256_cmp_pd(q, _mm256_set1_pd(Table::pieces[k - 1].end), _CMP_GE_OQ);
    f = _mm256_blendv_pd(f, fk, in), v = _mm256_blendv_pd(v, vk, in);
    a = _mm256_blendv_pd(a, _mm256_set1_pd(pc.mass_const), in);
    outer = _mm256_or_pd(outer, in);
  }
  const __m256d h_inv3 = _mm256_mul_pd(h_inv, _mm256_mul_pd(h_inv, h_inv));
  const __m256d ir3 = _mm256_mul_pd(inv_r, _mm256_mul_pd(inv_r, inv_r));
  const __m256d inside_f = _mm256_fmadd_pd(f, h_inv3, _mm256_and_pd(outer, _mm256_mul_pd(a, ir3)));
  const __m256d inside_v = _mm256_fmsub_pd(v, h_inv, _mm256_and_pd(outer, _mm256_mul_pd(a, inv_r)));
  const __m256d out = _mm256_cmp_pd(r, _mm256_mul_pd(_mm256_set1_pd(K::support), h), _CMP_GE_OQ);
  return {_mm256_blendv_pd(inside_f, ir3, out), _mm256_blendv_pd(inside_v, _mm256_sub_pd(_mm256_setzero_pd(), inv_r), out)};
}

template <class K>
__attribute__((target("avx2,fma"))) void softened_list_avx2(const ParticleArrays& p, const std::uint32_t* inside,
                                                            std::uint32_t n, const Real xa[3], Real ha, Real ha_inv,
                                                            NewtonianSums& s) {
  const __m256d X = _mm256_set1_pd(xa[0]), Y = _mm256_set1_pd(xa[1]), Z = _mm256_set1_pd(xa[2]);
  const __m256d Ha = _mm256_set1_pd(ha), Ha_inv = _mm256_set1_pd(ha_inv), half = _mm256_set1_pd(0.5);
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1);
  __m256d fx = zero, fy = zero, fz = zero, pot = zero;
  for (std::uint32_t k = 0; k < n; k += 4) {
    // the lanes past n (readable: the list has 4 spare slots) take the first lane's particle
    // (loaded as a vector: four scalar stores and a reload would stall on store forwarding)
    const __m128i past = _mm_cmpgt_epi32(_mm_set_epi32(3, 2, 1, 0), _mm_set1_epi32(static_cast<int>(n - k - 1)));
    const __m128i id = _mm_blendv_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(inside + k)),
                                       _mm_set1_epi32(static_cast<std::int32_t>(inside[k])), past);
    const __m256d valid = _mm256_castsi256_pd(first_lanes_mask(static_cast<long long>(n - k)));
    const __m256d dx = _mm256_sub_pd(X, _mm256_i32gather_pd(p.x, id, 8)), dy = _mm256_sub_pd(Y, _mm256_i32gather_pd(p.y, id, 8));
    const __m256d dz = _mm256_sub_pd(Z, _mm256_i32gather_pd(p.z, id, 8));
    const __m256d r2 = _mm256_fmadd_pd(dx, dx, _mm256_fmadd_pd(dy, dy, _mm256_mul_pd(dz, dz)));
    const __m256d positive = _mm256_cmp_pd(r2, zero, _CMP_GT_OQ);
    const __m256d r = _mm256_sqrt_pd(r2), inv_r = _mm256_and_pd(positive, _mm256_div_pd(one, _mm256_blendv_pd(one, r, positive)));
    const Pair4 sa = one_side4<K>(r, inv_r, Ha, Ha_inv);
    const Pair4 sb = one_side4<K>(r, inv_r, _mm256_i32gather_pd(p.h, id, 8), _mm256_i32gather_pd(p.h_inv, id, 8));
    const __m256d m = _mm256_and_pd(valid, _mm256_i32gather_pd(p.m, id, 8));
    const __m256d c = _mm256_mul_pd(m, _mm256_mul_pd(half, _mm256_add_pd(sa.force_over_r, sb.force_over_r)));
    fx = _mm256_fmadd_pd(c, dx, fx), fy = _mm256_fmadd_pd(c, dy, fy), fz = _mm256_fmadd_pd(c, dz, fz);
    pot = _mm256_fmadd_pd(m, _mm256_mul_pd(half, _mm256_add_pd(sa.phi, sb.phi)), pot);
  }
  s.fx += lane_sum(fx), s.fy += lane_sum(fy), s.fz += lane_sum(fz), s.pot += lane_sum(pot);
}

}  // namespace

// Not itself AVX2 code (a template declared without the target attribute): calls the one that is.
template <class K>
void add_softened_list_avx2(const ParticleArrays& p, const std::uint32_t* inside, std::uint32_t n, const Real xa[3],
                            Real ha, Real ha_inv, NewtonianSums& s) {
  softened_list_avx2<K>(p, inside, n, xa, ha, ha_inv, s);
}

#define SPHARK_INSTANTIATE(K)                                                                                   \
  template void add_softened_list_avx2<K>(const ParticleArrays&, const std::uint32_t*, std::uint32_t, const Real*, \
                                          Real, Real, NewtonianSums&);
SPHARK_GRAVITY_KERNELS(SPHARK_INSTANTIATE)
#undef SPHARK_INSTANTIATE

}  // namespace sphark::gravity_detail
#endif
