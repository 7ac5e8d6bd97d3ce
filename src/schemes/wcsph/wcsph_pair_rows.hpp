#pragma once
// The two pair loops of WcsphSystem, one particle's row of neighbours at a time, in lanes of W
// neighbours (simd/lanes.hpp): S = Real is the scalar path, simd::Real2 the SSE2 path and
// simd::Real4 the AVX2 path (wcsph_pair_rows_avx2.cpp; chosen at run time, simd/dispatch.hpp).
// The pair terms are the operators of sphark/operators/, written once for every width.
//
// Each row is first compacted to the neighbours inside the kernel support (neighbours_inside);
// a block is then W consecutive entries of that (the last one padded with its last neighbour);
// each lane gathers its neighbour's fields (W loads and inserts per field, no hardware gather),
// and lanes past the end get a zero kernel gradient, so they add exact zeros. Every lane sums
// its own share of the row; the lanes are added at the end of the row in a fixed order: results
// do not depend on the thread count, nor on the Verlet skin.
#include <cstddef>
#include <cstdint>

#include "sphark/core/types.hpp"
#include "sphark/neighbours/periodic_box.hpp"
#include "sphark/operators/artificial_viscosity.hpp"
#include "sphark/operators/conjugate_cleaning.hpp"
#include "sphark/operators/density_diffusion.hpp"
#include "sphark/operators/pressure_force.hpp"
#include "sphark/operators/renormalised_gradient.hpp"
#include "sphark/simd/lanes.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // lane-valued lambdas, inlined into their rows

namespace sphark::wcsph_detail {

// What the pair loops read: per-particle fields (x, v, grad_rho: D per particle), the lists.
template <int D>
struct RowInput {
  const Real *x, *v, *rho, *volume, *p_over_rho2, *q_psi, *sound_speed, *grad_rho;
  const std::uint32_t* indices;
  const std::size_t* offsets;
  MinimumImage<D> image;
  Real mass, h, inv_h, grad_scale, support2, alpha;  // grad_scale = 1/h^(D+2)
  bool cleaning, subsystem, viscosity, diffusion, corrected;
};

// The sums of one row of the force loop.
template <int D>
struct ForceRow {
  Vec<D> acc;         // eqs. (27), (39) and viscosity
  Real continuity;    // sum_b m v_ab . grad_a W_ab: eq. (28) and, divided by -rho_a, div v of eq. (36)
  Real diffusion;     // the density-diffusion sum
};

// One block of W interacting neighbours of particle a.
template <class S, int D>
struct Block {
  const std::uint32_t* b;        // the W neighbour indices
  simd::LaneVec<S, D> x_ab;      // x_a - x_b (minimum image)
  S F;                           // (dW/dr)/r; zero in the lanes past the row's end
  simd::LaneVec<S, D> grad_w;    // grad_a W_ab = F x_ab
};

// The W candidates of the list from entry k on, padded with the last: true for a full block.
template <int W>
inline bool candidates(const std::uint32_t* list, std::size_t k, std::size_t end, const std::uint32_t*& b,
                       std::uint32_t (&tail)[W]) {
  b = list + k;
  if (k + W <= end) return true;
  for (int l = 0; l < W; ++l) tail[l] = list[k + l < end ? k + l : end - 1];
  b = tail;
  return false;
}

// Lanes l < valid: true.
template <class S>
inline auto first_lanes(std::size_t valid) {
  return simd::lane_numbers<S>() < simd::broadcast<S>(static_cast<Real>(valid));
}

// Particle a's neighbours closer than the kernel support, in list order, into `inside` (room for
// the row's length plus W); returns their number. The pair loops see only these (once per RHS
// for both), so that how a row falls into lanes (and how the lanes' sums round) does not
// depend on the Verlet skin: a reused list gives the same result as a fresh one, bit for bit.
template <class S, int D>
inline std::size_t neighbours_inside(const RowInput<D>& in, std::size_t a, std::uint32_t* inside) {
  using V = simd::LaneVec<S, D>;
  constexpr int W = simd::width<S>;
  const V x_a = V::broadcast(Eigen::Map<const Vec<D>>(in.x + D * a));
  const std::size_t end = in.offsets[a + 1];
  std::uint32_t tail[W];
  const std::uint32_t* b = nullptr;
  std::size_t n = 0;
  for (std::size_t k = in.offsets[a]; k < end; k += W) {
    const bool full = candidates<W>(in.indices, k, end, b, tail);
    auto close = in.image(x_a - V::gather(in.x, b)).squaredNorm() < in.support2;
    if (!full) close = close & first_lanes<S>(end - k);
    n = simd::append_lanes<W>(simd::mask_bits(close), b, inside, n);
  }
  return n;
}

// Particle a's interacting neighbours: inside[0 .. end) of neighbours_inside.
struct InsideRow {
  const std::uint32_t* inside;
  std::size_t end;
};

template <class S, int D, class K, class PairTerms>
inline void for_each_block(const RowInput<D>& in, std::size_t a, InsideRow row, PairTerms&& pair_terms) {
  using V = simd::LaneVec<S, D>;
  constexpr int W = simd::width<S>;
  const V x_a = V::broadcast(Eigen::Map<const Vec<D>>(in.x + D * a));
  const std::uint32_t* inside = row.inside;
  const std::size_t end = row.end;
  std::uint32_t tail[W];
  for (std::size_t k = 0; k < end; k += W) {
    Block<S, D> p{nullptr, V::zero(), S{}, V::zero()};
    const bool full = candidates<W>(inside, k, end, p.b, tail);
    p.x_ab = in.image(x_a - V::gather(in.x, p.b));
    const S q = simd::sqrt(p.x_ab.squaredNorm()) * in.inv_h;
    p.F = in.grad_scale * K::unit_f_over_r(q, 1.0 / q);
    if (!full) p.F = first_lanes<S>(end - k) ? p.F : S{};
    p.grad_w = p.F * p.x_ab;
    pair_terms(p);
  }
}

// <grad rho>^L_a of Antuono et al. (2010), eq. (12) (renormalised_gradient.hpp).
template <class S, int D, class K>
inline Vec<D> density_gradient_row(const RowInput<D>& in, std::size_t a, InsideRow row) {
  RenormalisedGradient<D, S> g;
  const S rho_a = simd::broadcast<S>(in.rho[a]);
  for_each_block<S, D, K>(in, a, row, [&](const Block<S, D>& p) {
    g.add(simd::gather<S>(in.volume, p.b, 1), rho_a, simd::gather<S>(in.rho, p.b, 1), p.x_ab, p.grad_w);
  });
  return g.summed().finish();
}

template <class S, int D, class K>
inline ForceRow<D> force_row(const RowInput<D>& in, std::size_t a, InsideRow row) {
  using V = simd::LaneVec<S, D>;
  auto lanes = [](Real x) { return simd::broadcast<S>(x); };
  auto field = [&](const Real* f, const std::uint32_t* b) { return simd::gather<S>(f, b, 1); };
  const S m = lanes(in.mass), rho_a = lanes(in.rho[a]), alpha = lanes(in.alpha), h = lanes(in.h);
  const S p_a = lanes(in.p_over_rho2[a]), q_a = in.cleaning ? lanes(in.q_psi[a]) : S{};
  const S c_a = in.viscosity ? lanes(in.sound_speed[a]) : S{};
  const V v_a = V::broadcast(Eigen::Map<const Vec<D>>(in.v + D * a));
  const V grad_rho_a = in.corrected ? V::broadcast(Eigen::Map<const Vec<D>>(in.grad_rho + D * a)) : V::zero();
  V acc = V::zero();
  S continuity{}, diffusion{};
  for_each_block<S, D, K>(in, a, row, [&](const Block<S, D>& p) {
    const V v_ab = v_a - V::gather(in.v, p.b);
    // seed 000, eq. (36): the summand of the difference divergence of v, which is also that of
    // the continuity equation (28) (sign of (36)): m v_ab . grad_a W_ab
    continuity += continuity_term<D>(m, v_ab, p.grad_w);
    if (in.cleaning) acc -= symmetric_gradient_term(m, q_a, p.grad_w, field(in.q_psi, p.b), p.grad_w);  // eq. (39)
    if (in.subsystem) return;
    acc += pressure_acceleration_term<D>(m, p_a, field(in.p_over_rho2, p.b), p.grad_w);  // eq. (27)
    const S rho_b = field(in.rho, p.b);
    if (in.viscosity) {
      const S c_ab = 0.5 * (c_a + field(in.sound_speed, p.b));
      acc += monaghan_viscosity_term<D>(m, alpha, c_ab, 0.5 * (rho_a + rho_b), h, p.x_ab, v_ab, p.grad_w);
    }
    if (in.diffusion) {
      const S volume_b = field(in.volume, p.b);
      diffusion += in.corrected ? density_diffusion_term_radial(volume_b, rho_a, rho_b, grad_rho_a,
                                                                V::gather(in.grad_rho, p.b), p.F, p.grad_w)
                                : density_diffusion_term_radial(volume_b, rho_a, rho_b, p.F);
    }
  });
  return {acc.sum(), simd::sum(continuity), simd::sum(diffusion)};
}

// The AVX2 + FMA rows (wcsph_pair_rows_avx2.cpp): call only when the CPU has both.
template <int D>
std::size_t neighbours_inside_avx2(const RowInput<D>& in, std::size_t a, std::uint32_t* inside);
template <int D, class K>
Vec<D> density_gradient_row_avx2(const RowInput<D>& in, std::size_t a, InsideRow row);
template <int D, class K>
ForceRow<D> force_row_avx2(const RowInput<D>& in, std::size_t a, InsideRow row);

}  // namespace sphark::wcsph_detail

#pragma GCC diagnostic pop
