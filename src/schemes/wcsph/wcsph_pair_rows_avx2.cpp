// The WCSPH pair rows on four lanes with AVX2 + FMA, and the same compiled for AVX-512VL
// (wcsph_pair_rows.hpp), for CPUs that have them (chosen at run time, simd/dispatch.hpp). Each
// row is one flattened function compiled for its instruction set, so every pair term of the row
// is inlined into it as that code; the entry points are baseline functions (declared without the
// target attribute) that call it.
// (The pair terms' Real4 instantiations pass AVX vectors: -Wpsabi notes that their ABI
// differs without AVX; they are inlined into the rows, never called across that boundary.)
#pragma GCC diagnostic ignored "-Wpsabi"
#include "wcsph_pair_rows.hpp"

#include "sphark/kernels/kernel_list.hpp"

#define SPHARK_AVX2 "avx2,fma"
// AVX-512VL: the same four lanes (256-bit vectors) with 32 vector registers and mask registers
#define SPHARK_AVX512 "avx2,fma,avx512f,avx512dq,avx512vl"

namespace sphark::wcsph_detail {

#if defined(SPHARK_SIMD_HAVE_AVX2)
namespace {
template <int D>
__attribute__((target(SPHARK_AVX2), flatten)) std::size_t inside_on_avx2(const RowInput<D>& in, std::size_t a,
                                                                   std::uint32_t* inside) {
  return neighbours_inside<simd::Real4, D>(in, a, inside);
}
template <int D, class K>
__attribute__((target(SPHARK_AVX2), flatten)) Vec<D> gradient_on_avx2(const RowInput<D>& in, std::size_t a, InsideRow row) {
  return density_gradient_row<simd::Real4, D, K>(in, a, row);
}
template <int D, class K>
__attribute__((target(SPHARK_AVX2), flatten)) ForceRow<D> forces_on_avx2(const RowInput<D>& in, std::size_t a,
                                                                   InsideRow row) {
  return force_row<simd::Real4, D, K>(in, a, row);
}
template <int D>
__attribute__((target(SPHARK_AVX512), flatten)) std::size_t inside_on_avx512vl(const RowInput<D>& in, std::size_t a,
                                                                     std::uint32_t* inside) {
  return neighbours_inside<simd::Real4, D>(in, a, inside);
}
template <int D, class K>
__attribute__((target(SPHARK_AVX512), flatten)) Vec<D> gradient_on_avx512vl(const RowInput<D>& in, std::size_t a,
                                                                  InsideRow row) {
  return density_gradient_row<simd::Real4, D, K>(in, a, row);
}
template <int D, class K>
__attribute__((target(SPHARK_AVX512), flatten)) ForceRow<D> forces_on_avx512vl(const RowInput<D>& in, std::size_t a,
                                                                     InsideRow row) {
  return force_row<simd::Real4, D, K>(in, a, row);
}
}  // namespace

template <int D>
std::size_t neighbours_inside_avx2(const RowInput<D>& in, std::size_t a, std::uint32_t* inside) {
  return inside_on_avx2<D>(in, a, inside);
}
template <int D, class K>
Vec<D> density_gradient_row_avx2(const RowInput<D>& in, std::size_t a, InsideRow row) {
  return gradient_on_avx2<D, K>(in, a, row);
}
template <int D, class K>
ForceRow<D> force_row_avx2(const RowInput<D>& in, std::size_t a, InsideRow row) {
  return forces_on_avx2<D, K>(in, a, row);
}
template <int D>
std::size_t neighbours_inside_avx512(const RowInput<D>& in, std::size_t a, std::uint32_t* inside) {
  return inside_on_avx512vl<D>(in, a, inside);
}
template <int D, class K>
Vec<D> density_gradient_row_avx512(const RowInput<D>& in, std::size_t a, InsideRow row) {
  return gradient_on_avx512vl<D, K>(in, a, row);
}
template <int D, class K>
ForceRow<D> force_row_avx512(const RowInput<D>& in, std::size_t a, InsideRow row) {
  return forces_on_avx512vl<D, K>(in, a, row);
}
#else  // no x86-64 vector paths: never chosen (simd/dispatch.hpp), defined for the linker
template <int D>
std::size_t neighbours_inside_avx2(const RowInput<D>& in, std::size_t a, std::uint32_t* inside) {
  return neighbours_inside<Real, D>(in, a, inside);
}
template <int D, class K>
Vec<D> density_gradient_row_avx2(const RowInput<D>& in, std::size_t a, InsideRow row) {
  return density_gradient_row<Real, D, K>(in, a, row);
}
template <int D, class K>
ForceRow<D> force_row_avx2(const RowInput<D>& in, std::size_t a, InsideRow row) {
  return force_row<Real, D, K>(in, a, row);
}
template <int D>
std::size_t neighbours_inside_avx512(const RowInput<D>& in, std::size_t a, std::uint32_t* inside) {
  return neighbours_inside<Real, D>(in, a, inside);
}
template <int D, class K>
Vec<D> density_gradient_row_avx512(const RowInput<D>& in, std::size_t a, InsideRow row) {
  return density_gradient_row<Real, D, K>(in, a, row);
}
template <int D, class K>
ForceRow<D> force_row_avx512(const RowInput<D>& in, std::size_t a, InsideRow row) {
  return force_row<Real, D, K>(in, a, row);
}
#endif

#define SPHARK_WCSPH_INSIDE(D)                                                                  \
  template std::size_t neighbours_inside_avx2<D>(const RowInput<D>&, std::size_t, std::uint32_t*); \
  template std::size_t neighbours_inside_avx512<D>(const RowInput<D>&, std::size_t, std::uint32_t*);
SPHARK_WCSPH_INSIDE(2)
SPHARK_WCSPH_INSIDE(3)
#define SPHARK_WCSPH_ROWS(D, K)                                                          \
  template Vec<D> density_gradient_row_avx2<D, K>(const RowInput<D>&, std::size_t, InsideRow);   \
  template ForceRow<D> force_row_avx2<D, K>(const RowInput<D>&, std::size_t, InsideRow);         \
  template Vec<D> density_gradient_row_avx512<D, K>(const RowInput<D>&, std::size_t, InsideRow); \
  template ForceRow<D> force_row_avx512<D, K>(const RowInput<D>&, std::size_t, InsideRow);
#define SPHARK_WCSPH_ROWS_2D_3D(K) SPHARK_WCSPH_ROWS(2, K<2>) SPHARK_WCSPH_ROWS(3, K<3>)
SPHARK_KERNELS(SPHARK_WCSPH_ROWS_2D_3D)
#undef SPHARK_WCSPH_ROWS_2D_3D
#undef SPHARK_WCSPH_ROWS
#undef SPHARK_WCSPH_INSIDE

}  // namespace sphark::wcsph_detail
