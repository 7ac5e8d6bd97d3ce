#pragma once
// What WcsphSystem's passes share (private to src/schemes/wcsph): the pair rows of the vector
// path in use, and what a force row writes per particle.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>

#include "sphark/core/types.hpp"
#include "sphark/simd/dispatch.hpp"
#include "wcsph_pair_rows.hpp"

namespace sphark::wcsph_detail {

// The rows of the path in use (wcsph_pair_rows.hpp).
template <int D, class K>
struct Rows {
  std::size_t (*inside)(const RowInput<D>&, std::size_t, std::uint32_t*);
  Vec<D> (*gradient)(const RowInput<D>&, std::size_t, InsideRow);
  ForceRow<D> (*forces)(const RowInput<D>&, std::size_t, InsideRow);
};

template <int D, class K>
Rows<D, K> rows_in_use() {
  switch (pair_loop_simd()) {
    case PairLoopSimd::Avx512:
      return {neighbours_inside_avx512<D>, density_gradient_row_avx512<D, K>, force_row_avx512<D, K>};
    case PairLoopSimd::Avx2:
      return {neighbours_inside_avx2<D>, density_gradient_row_avx2<D, K>, force_row_avx2<D, K>};
    case PairLoopSimd::Sse2:
      return {neighbours_inside<simd::Real2, D>, density_gradient_row<simd::Real2, D, K>,
              force_row<simd::Real2, D, K>};
    case PairLoopSimd::Scalar: break;
  }
  return {neighbours_inside<Real, D>, density_gradient_row<Real, D, K>, force_row<Real, D, K>};
}

// Row a's <grad rho>^L (density_gradient_row), also written into a's record for its neighbours.
template <int D, class K>
Vec<D> gradient_into_record(const Rows<D, K>& rows, const RowInput<D>& in, std::size_t a, InsideRow row, Real* records) {
  const Vec<D> g = rows.gradient(in, a, row);
  Eigen::Map<Vec<D>>(records + Record<D>::size * a + Record<D>::grad_rho) = g;
  return g;
}

// Particle p's derivatives from its force row's sums; returns |dv_p/dt|^2.
template <int D>
struct ForceStore {
  const Real *x, *v, *rho, *psi;  // state fields (psi: with cleaning)
  Real *dx, *dv, *drho, *dpsi;    // their derivatives
  Real* div_v;                    // per particle, eq. (36)
  const std::function<Vec<D>(const Vec<D>&)>* body_force;
  Real c_h, cleaning_rate, dh_c;  // dh_c = delta h c_0 of the density diffusion
  bool clean, subsystem;

  Real operator()(std::size_t p, const ForceRow<D>& sums) const {
    Vec<D> acc = sums.acc;
    div_v[p] = -sums.continuity / rho[p];  // eq. (36)
    if (!subsystem && *body_force) acc += (*body_force)(Eigen::Map<const Vec<D>>(x + D * p));
    Eigen::Map<Vec<D>>(dv + D * p) = acc;
    Eigen::Map<Vec<D>> dx_p(dx + D * p);
    if (subsystem)
      dx_p.setZero();
    else
      dx_p = Eigen::Map<const Vec<D>>(v + D * p);
    drho[p] = subsystem ? 0.0 : sums.continuity + dh_c * sums.diffusion;  // eq. (28) + delta-SPH
    if (clean) dpsi[p] = -c_h * c_h * rho[p] * div_v[p] - cleaning_rate * psi[p];  // eq. (30)
    return acc.squaredNorm();
  }
};

}  // namespace sphark::wcsph_detail
