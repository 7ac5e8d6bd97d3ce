// The WCSPH pair rows on four lanes with AVX2 and FMA (wcsph_pair_rows.hpp), for CPUs that have
// both (chosen at run time, simd/dispatch.hpp). Each row is one flattened function compiled for
// AVX2 + FMA, so every pair term of the row is inlined into it as AVX2 code; the entry points
// are baseline functions (declared without the target attribute) that call it.
// (The pair terms' Real4 instantiations pass AVX vectors: -Wpsabi notes that their ABI differs
// without AVX; they are inlined into the AVX2 rows, never called across that boundary.)
#pragma GCC diagnostic ignored "-Wpsabi"
#include "wcsph_pair_rows.hpp"

#include "sphark/kernels/kernel_list.hpp"

namespace sphark::wcsph_detail {

#if defined(SPHARK_SIMD_HAVE_AVX2)
namespace {
template <int D>
__attribute__((target("avx2,fma"), flatten)) std::size_t inside_avx2(const RowInput<D>& in, std::size_t a,
                                                                       std::uint32_t* inside) {
  return neighbours_inside<simd::Real4, D>(in, a, inside);
}
template <int D, class K>
__attribute__((target("avx2,fma"), flatten)) Vec<D> gradient_row_avx2(const RowInput<D>& in, std::size_t a, InsideRow row) {
  return density_gradient_row<simd::Real4, D, K>(in, a, row);
}
template <int D, class K>
__attribute__((target("avx2,fma"), flatten)) ForceRow<D> forces_row_avx2(const RowInput<D>& in, std::size_t a, InsideRow row) {
  return force_row<simd::Real4, D, K>(in, a, row);
}
}  // namespace

template <int D>
std::size_t neighbours_inside_avx2(const RowInput<D>& in, std::size_t a, std::uint32_t* inside) {
  return inside_avx2<D>(in, a, inside);
}
template <int D, class K>
Vec<D> density_gradient_row_avx2(const RowInput<D>& in, std::size_t a, InsideRow row) {
  return gradient_row_avx2<D, K>(in, a, row);
}
template <int D, class K>
ForceRow<D> force_row_avx2(const RowInput<D>& in, std::size_t a, InsideRow row) {
  return forces_row_avx2<D, K>(in, a, row);
}
#else
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
#endif

template std::size_t neighbours_inside_avx2<2>(const RowInput<2>&, std::size_t, std::uint32_t*);
template std::size_t neighbours_inside_avx2<3>(const RowInput<3>&, std::size_t, std::uint32_t*);
#define SPHARK_WCSPH_ROWS(D, K)                                                              \
  template Vec<D> density_gradient_row_avx2<D, K>(const RowInput<D>&, std::size_t, InsideRow);          \
  template ForceRow<D> force_row_avx2<D, K>(const RowInput<D>&, std::size_t, InsideRow);
#define SPHARK_WCSPH_ROWS_2D_3D(K) SPHARK_WCSPH_ROWS(2, K<2>) SPHARK_WCSPH_ROWS(3, K<3>)
SPHARK_KERNELS(SPHARK_WCSPH_ROWS_2D_3D)
#undef SPHARK_WCSPH_ROWS_2D_3D
#undef SPHARK_WCSPH_ROWS

}  // namespace sphark::wcsph_detail
