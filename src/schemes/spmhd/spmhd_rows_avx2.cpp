// The SPMHD loops on four lanes with AVX2 + FMA, and the same compiled for AVX-512VL, for CPUs
// that have them (chosen at run time, simd/dispatch.hpp): flattened functions compiled for their
// instruction set, so that the generic lane code of spmhd_density_sums.hpp and
// spmhd_pair_row.hpp is inlined into them as that code; the entry points are baseline functions
// (declared without the target attribute) that call them.
// (The Real4 instantiations pass AVX vectors: -Wpsabi notes that their ABI differs
// without AVX; they are inlined into the flattened functions, never called across that boundary.)
#pragma GCC diagnostic ignored "-Wpsabi"
#include "sphark/kernels/kernel_list.hpp"
#include "spmhd_density_sums.hpp"
#include "spmhd_pair_row.hpp"

#define SPHARK_AVX2 "avx2,fma"
// AVX-512VL: the same four lanes (256-bit vectors) with 32 vector registers and mask registers
#define SPHARK_AVX512 "avx2,fma,avx512f,avx512dq,avx512vl"

namespace sphark::spmhd_detail {

#if defined(SPHARK_SIMD_HAVE_AVX2)
namespace {
template <int D, class K>
__attribute__((target(SPHARK_AVX2), flatten)) DensitySums sums_on_avx2(const Real* r, const Real* m, std::size_t n,
                                                                 Real h_inv, Real self_mass) {
  return density_sums<simd::Real4, D, K>(r, m, n, h_inv, self_mass);
}
template <int D, class K>
__attribute__((target(SPHARK_AVX2), flatten)) PairSums<D> row_on_avx2(const RowInput<D>& in, std::size_t a,
                                                                std::uint32_t* inside) {
  return pair_row<simd::Real4, D, K>(in, a, inside);
}
template <int D, class K>
__attribute__((target(SPHARK_AVX512), flatten)) DensitySums sums_on_avx512vl(const Real* r, const Real* m, std::size_t n,
                                                                   Real h_inv, Real self_mass) {
  return density_sums<simd::Real4, D, K>(r, m, n, h_inv, self_mass);
}
template <int D, class K>
__attribute__((target(SPHARK_AVX512), flatten)) PairSums<D> row_on_avx512vl(const RowInput<D>& in, std::size_t a,
                                                                  std::uint32_t* inside) {
  return pair_row<simd::Real4, D, K>(in, a, inside);
}
}  // namespace

template <int D, class K>
DensitySums density_sums_avx2(const Real* r, const Real* m, std::size_t n, Real h_inv, Real self_mass) {
  return sums_on_avx2<D, K>(r, m, n, h_inv, self_mass);
}
template <int D, class K>
PairSums<D> pair_row_avx2(const RowInput<D>& in, std::size_t a, std::uint32_t* inside) {
  return row_on_avx2<D, K>(in, a, inside);
}
template <int D, class K>
DensitySums density_sums_avx512(const Real* r, const Real* m, std::size_t n, Real h_inv, Real self_mass) {
  return sums_on_avx512vl<D, K>(r, m, n, h_inv, self_mass);
}
template <int D, class K>
PairSums<D> pair_row_avx512(const RowInput<D>& in, std::size_t a, std::uint32_t* inside) {
  return row_on_avx512vl<D, K>(in, a, inside);
}
#else  // no x86-64 vector paths: never chosen (simd/dispatch.hpp), defined for the linker
template <int D, class K>
DensitySums density_sums_avx2(const Real* r, const Real* m, std::size_t n, Real h_inv, Real self_mass) {
  return density_sums<Real, D, K>(r, m, n, h_inv, self_mass);
}
template <int D, class K>
PairSums<D> pair_row_avx2(const RowInput<D>& in, std::size_t a, std::uint32_t* inside) {
  return pair_row<Real, D, K>(in, a, inside);
}
template <int D, class K>
DensitySums density_sums_avx512(const Real* r, const Real* m, std::size_t n, Real h_inv, Real self_mass) {
  return density_sums<Real, D, K>(r, m, n, h_inv, self_mass);
}
template <int D, class K>
PairSums<D> pair_row_avx512(const RowInput<D>& in, std::size_t a, std::uint32_t* inside) {
  return pair_row<Real, D, K>(in, a, inside);
}
#endif

#define SPHARK_SPMHD_ROWS(D, K)                                                                     \
  template DensitySums density_sums_avx2<D, K>(const Real*, const Real*, std::size_t, Real, Real);   \
  template PairSums<D> pair_row_avx2<D, K>(const RowInput<D>&, std::size_t, std::uint32_t*);         \
  template DensitySums density_sums_avx512<D, K>(const Real*, const Real*, std::size_t, Real, Real); \
  template PairSums<D> pair_row_avx512<D, K>(const RowInput<D>&, std::size_t, std::uint32_t*);
#define SPHARK_SPMHD_ROWS_2D_3D(K) SPHARK_SPMHD_ROWS(2, K<2>) SPHARK_SPMHD_ROWS(3, K<3>)
SPHARK_KERNELS(SPHARK_SPMHD_ROWS_2D_3D)
#undef SPHARK_SPMHD_ROWS_2D_3D
#undef SPHARK_SPMHD_ROWS

}  // namespace sphark::spmhd_detail
