#include "cell_scan.hpp"

#include "sphark/simd/dispatch.hpp"
#include "sphark/simd/lanes.hpp"

namespace sphark::neighbours_detail {

namespace {

constexpr std::uint32_t kChunk = 64;  // candidates tested before their hits are compacted

// The squared separations' test for slots [s0, s0 + n) into flags: branch-free, over consecutive
// memory, so the compiler vectorises it (the lanes of the path it is compiled for).
template <int D, bool PerParticleRadius, bool Periodic>
inline void test_chunk(const CellPoints<D>& c, std::uint32_t s0, std::uint32_t n, const Real* xi, Real r2_i,
                       const MinimumImage<D>& image, std::uint8_t* flags) {
  for (std::uint32_t l = 0; l < n; ++l) {
    const std::uint32_t s = s0 + l;
    Real d2 = 0;
    for (int k = 0; k < D; ++k) {
      Real d = xi[k] - c.x[k][s];
      if constexpr (Periodic) d -= image.L[k] * round_to_nearest(d * image.inv_L[k]);
      d2 = d2 + d * d;
    }
    Real reach2 = r2_i;
    if constexpr (PerParticleRadius) reach2 = c.r2[s] > r2_i ? c.r2[s] : r2_i;
    flags[l] = d2 < reach2;
  }
}

template <int D, bool PerParticleRadius, bool Periodic>
inline std::uint32_t* scan(const CellPoints<D>& c, std::uint32_t s0, std::uint32_t s1, const Real* xi, Real r2_i,
                           std::uint32_t i, const MinimumImage<D>& image, std::uint32_t* out) {
  std::uint8_t flags[kChunk];
  for (std::uint32_t first = s0; first < s1; first += kChunk) {
    const std::uint32_t n = s1 - first < kChunk ? s1 - first : kChunk;
    test_chunk<D, PerParticleRadius, Periodic>(c, first, n, xi, r2_i, image, flags);
    for (std::uint32_t l = 0; l < n; ++l) {  // branch-free append: write every candidate, keep the hits
      const std::uint32_t j = c.particle[first + l];
      *out = j;
      out += flags[l] & (j != i);
    }
  }
  return out;
}

// Scan<D, PerParticleRadius, Periodic>::run for the case at hand (one radius or each particle's;
// a periodic axis or none).
template <int D, template <int, bool, bool> class Scan>
inline std::uint32_t* scan_case(const CellPoints<D>& c, std::uint32_t s0, std::uint32_t s1, const Real* xi, Real r2_i,
                                std::uint32_t i, const MinimumImage<D>& image, std::uint32_t* out) {
  if (c.r2)
    return image.periodic ? Scan<D, true, true>::run(c, s0, s1, xi, r2_i, i, image, out)
                          : Scan<D, true, false>::run(c, s0, s1, xi, r2_i, i, image, out);
  return image.periodic ? Scan<D, false, true>::run(c, s0, s1, xi, r2_i, i, image, out)
                        : Scan<D, false, false>::run(c, s0, s1, xi, r2_i, i, image, out);
}

template <int D, bool PerParticleRadius, bool Periodic>
struct BaselineScan {
  static std::uint32_t* run(const CellPoints<D>& c, std::uint32_t s0, std::uint32_t s1, const Real* xi, Real r2_i,
                            std::uint32_t i, const MinimumImage<D>& image, std::uint32_t* out) {
    return scan<D, PerParticleRadius, Periodic>(c, s0, s1, xi, r2_i, i, image, out);
  }
};

template <int D>
std::uint32_t* scan_baseline(const CellPoints<D>& c, std::uint32_t s0, std::uint32_t s1, const Real* xi, Real r2_i,
                             std::uint32_t i, const MinimumImage<D>& image, std::uint32_t* out) {
  return scan_case<D, BaselineScan>(c, s0, s1, xi, r2_i, i, image, out);
}

#if defined(__GNUC__) && defined(__x86_64__)
// AVX2 without FMA (the same roundings as the baseline, see cell_scan.hpp): four candidates at a
// time, their hits' bits from the comparison's sign mask, appended by one shuffle of their
// indices (simd::append_lanes); the rest of the range as the baseline does it.
typedef std::uint32_t U4 __attribute__((vector_size(16)));
typedef float F4 __attribute__((vector_size(16)));

template <int D, bool PerParticleRadius, bool Periodic>
__attribute__((target("avx2"), always_inline)) inline std::uint32_t* scan4(const CellPoints<D>& c, std::uint32_t s0,
                                                                            std::uint32_t s1, const Real* xi, Real r2_i,
                                                                            std::uint32_t i, const MinimumImage<D>& image,
                                                                            std::uint32_t* out) {
  using simd::Real4;
  const U4 self = U4{} + i;
  std::uint32_t s = s0;
  for (; s + 4 <= s1; s += 4) {
    Real4 d2{};
    for (int k = 0; k < D; ++k) {
      Real4 d = (Real4{} + xi[k]) - simd::load<Real4>(c.x[k] + s);
      if constexpr (Periodic) d -= image.L[k] * round_to_nearest_lanes(d * image.inv_L[k]);
      d2 = d2 + d * d;
    }
    Real4 reach2 = Real4{} + r2_i;
    if constexpr (PerParticleRadius) {
      const Real4 r2 = simd::load<Real4>(c.r2 + s);
      reach2 = r2 > reach2 ? r2 : reach2;
    }
    U4 ids;
    __builtin_memcpy(&ids, c.particle + s, sizeof ids);
    const unsigned hits = static_cast<unsigned>(__builtin_ia32_movmskpd256(reinterpret_cast<Real4>(d2 < reach2)));
    const unsigned self_lanes = static_cast<unsigned>(__builtin_ia32_movmskps(reinterpret_cast<F4>(ids == self)));
    out += simd::append_lanes<4>(hits & ~self_lanes, c.particle + s, out, 0);
  }
  return scan<D, PerParticleRadius, Periodic>(c, s, s1, xi, r2_i, i, image, out);
}

template <int D, bool PerParticleRadius, bool Periodic>
struct Avx2Scan {
  __attribute__((target("avx2"))) static std::uint32_t* run(
      const CellPoints<D>& c, std::uint32_t s0, std::uint32_t s1, const Real* xi, Real r2_i, std::uint32_t i,
      const MinimumImage<D>& image, std::uint32_t* out) {
    return scan4<D, PerParticleRadius, Periodic>(c, s0, s1, xi, r2_i, i, image, out);
  }
};

template <int D>
__attribute__((target("avx2"), flatten)) std::uint32_t* scan_avx2(const CellPoints<D>& c, std::uint32_t s0,
                                                                   std::uint32_t s1, const Real* xi, Real r2_i,
                                                                   std::uint32_t i, const MinimumImage<D>& image,
                                                                   std::uint32_t* out) {
  return scan_case<D, Avx2Scan>(c, s0, s1, xi, r2_i, i, image, out);
}
#endif
}  // namespace

template <int D>
ScanCell<D> scan_cell_for_this_cpu() {
#if defined(__GNUC__) && defined(__x86_64__)
  const PairLoopSimd path = pair_loop_simd();
  if (path == PairLoopSimd::Avx2 || path == PairLoopSimd::Avx512) return scan_avx2<D>;
#endif
  return scan_baseline<D>;
}

template ScanCell<1> scan_cell_for_this_cpu<1>();
template ScanCell<2> scan_cell_for_this_cpu<2>();
template ScanCell<3> scan_cell_for_this_cpu<3>();

}  // namespace sphark::neighbours_detail
