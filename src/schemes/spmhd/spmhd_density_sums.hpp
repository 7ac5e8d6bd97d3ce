#pragma once
// The density sum of the SPMHD h solve over a particle's gathered candidates, in lanes of W
// (simd/lanes.hpp; S = Real the scalar path, Real2 SSE2, Real4 AVX2 + FMA or AVX-512VL in
// spmhd_rows_avx2.cpp, chosen at run time). seed 000, eq. (4) and its h-derivative at unit h:
//   s0 = sum_b m_b w1(q_b),   s1 = sum_b m_b (D w1(q_b) + q_b^2 f1(q_b)),   q_b = r_b / h,
// with the self term (q = 0) first: rho = s0 / h^D, drho/dh = -s1 / h^(D+1). The candidate
// arrays r, m have room for W entries past n, which must hold m = 0 (they add exact zeros).
// Lane l sums the candidates l, l + W, ...; the lanes are added in a fixed order at the end.
#include <cstddef>

#include "sphark/core/types.hpp"
#include "sphark/simd/lanes.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace sphark::spmhd_detail {

struct DensitySums {
  Real s0, s1;
};

template <class S, int D, class K>
inline DensitySums density_sums(const Real* r, const Real* m, std::size_t n, Real h_inv, Real self_mass) {
  constexpr int W = simd::width<S>;
  S s0{}, s1{};
  const Real self_w = self_mass * K::unit_w(Real{0});
  if constexpr (W == 1) {
    s0 = self_w, s1 = D * self_w;
  } else {
    s0[0] = self_w, s1[0] = D * self_w;
  }
  for (std::size_t c = 0; c < n; c += W) {
    const S q = simd::load<S>(r + c) * h_inv, mass = simd::load<S>(m + c);
    const S w1 = K::unit_w(q);
    s0 += mass * w1;
    s1 += mass * (D * w1 + K::unit_q_dw(q));
  }
  return {simd::sum(s0), simd::sum(s1)};
}

// (spmhd_rows_avx2.cpp) Call only when the CPU has AVX2 and FMA, or AVX-512.
template <int D, class K>
DensitySums density_sums_avx2(const Real* r, const Real* m, std::size_t n, Real h_inv, Real self_mass);
template <int D, class K>
DensitySums density_sums_avx512(const Real* r, const Real* m, std::size_t n, Real h_inv, Real self_mass);

}  // namespace sphark::spmhd_detail

#pragma GCC diagnostic pop
