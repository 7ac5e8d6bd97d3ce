#pragma once
// The two pair loops of WcsphSystem, one particle's row of neighbours at a time, in lanes of W
// neighbours (simd/lanes.hpp): S = Real is the scalar path, simd::Real2 the SSE2 path and
// simd::Real4 the AVX2 path (wcsph_pair_rows_avx2.cpp; chosen at run time, simd/dispatch.hpp).
// The pair terms are the operators of sphark/operators/, written once for every width.
//
// Each row is first compacted to the neighbours inside the kernel support (neighbours_inside);
// a block is then W consecutive entries of that (the last one padded with its last neighbour);
// each lane gathers its neighbour's record (Record: the fields a neighbour reads, in groups of
// four doubles: one load per group and lane, then a transpose; measured faster than a load and
// insert per field, and than AVX2's hardware gather), and lanes past the end get a zero kernel
// gradient, so they add exact zeros. Every lane sums
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
#include "sphark/simd/lane_blocks.hpp"
#include "sphark/simd/lanes.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // lane-valued lambdas, inlined into their rows

namespace sphark::wcsph_detail {

// A particle's fields as its neighbours read them: one record of Record<D>::size doubles per
// particle, filled once per RHS, so that a block gathers a few groups of four fields
// (simd::gather_group) instead of every field separately.
template <int D>
struct Record {
  static constexpr int x = 0, rho = D, volume = D + 1, v = D + 2, p_over_rho2 = 2 * D + 2, q_psi = 2 * D + 3,
                       sound_speed = 2 * D + 4, grad_rho = 2 * D + 5;
  static constexpr int size = (3 * D + 5 + 3) / 4 * 4;
  static constexpr int groups_of(int fields) { return (fields + 3) / 4; }  // groups holding fields 0 .. fields-1
};

// What the pair loops read: the records (x, rho, V = m/rho, v, P/rho^2, psi/rho^2, c, <grad rho>),
// the lists, the constants.
template <int D>
struct RowInput {
  const Real* records;
  const std::uint32_t* indices;
  const std::size_t* offsets;
  MinimumImage<D> image;
  Real mass, h, inv_h, grad_scale, support2, alpha;  // grad_scale = 1/h^(D+2)
  bool cleaning, subsystem, viscosity, diffusion, corrected;
  const Real* record(std::size_t a) const { return records + Record<D>::size * a; }
};

// The sums of one row of the force loop.
template <int D>
struct ForceRow {
  Vec<D> acc;         // eqs. (27), (39) and viscosity
  Real continuity;    // sum_b m v_ab . grad_a W_ab: eq. (28) and, divided by -rho_a, div v of eq. (36)
  Real diffusion;     // the density-diffusion sum
};

// The first `Groups` groups of W neighbours' records, as lanes: field k of lane l is f[k][l].
template <class S, int Groups>
struct NeighbourFields : simd::GatheredFields<S, Groups> {
  template <int D>
  NeighbourFields(const RowInput<D>& in, const std::uint32_t* b)
      : simd::GatheredFields<S, Groups>(in.records, Record<D>::size, b) {}
};

// One block of W interacting neighbours of particle a.
template <class S, int D, int Groups>
struct Block {
  NeighbourFields<S, Groups> b;  // their records
  simd::LaneVec<S, D> x_ab;      // x_a - x_b (minimum image)
  S F;                           // (dW/dr)/r; zero in the lanes past the row's end
  simd::LaneVec<S, D> grad_w;    // grad_a W_ab = F x_ab
};

template <class S, int D>
inline simd::LaneVec<S, D> position_of(const RowInput<D>& in, std::size_t a) {
  return simd::LaneVec<S, D>::broadcast(Eigen::Map<const Vec<D>>(in.record(a) + Record<D>::x));
}

// Particle a's neighbours closer than the kernel support, in list order, into `inside` (room for
// the row's length plus W); returns their number. The pair loops see only these (once per RHS
// for both), so that how a row falls into lanes (and how the lanes' sums round) does not
// depend on the Verlet skin: a reused list gives the same result as a fresh one, bit for bit.
template <class S, int D>
inline std::size_t neighbours_inside(const RowInput<D>& in, std::size_t a, std::uint32_t* inside) {
  constexpr int W = simd::width<S>;
  const simd::LaneVec<S, D> x_a = position_of<S, D>(in, a);
  const std::size_t end = in.offsets[a + 1];
  std::uint32_t tail[W];
  const std::uint32_t* b = nullptr;
  std::size_t n = 0;
  for (std::size_t k = in.offsets[a]; k < end; k += W) {
    const bool full = simd::block_of<W>(in.indices, k, end, b, tail);
    const NeighbourFields<S, Record<D>::groups_of(D)> fields(in, b);
    auto close = in.image(x_a - fields.template vec<D>(Record<D>::x)).squaredNorm() < in.support2;
    if (!full) close = close & simd::first_lanes<S>(end - k);
    n = simd::append_lanes<W>(simd::mask_bits(close), b, inside, n);
  }
  return n;
}

// Particle a's interacting neighbours: inside[0 .. end) of neighbours_inside.
struct InsideRow {
  const std::uint32_t* inside;
  std::size_t end;
};

// pair_terms(block) for the blocks of a's interacting neighbours, each with its first Groups
// groups of record fields.
template <class S, int D, class K, int Groups, class PairTerms>
inline void for_each_block(const RowInput<D>& in, std::size_t a, InsideRow row, PairTerms&& pair_terms) {
  using V = simd::LaneVec<S, D>;
  constexpr int W = simd::width<S>;
  const V x_a = position_of<S, D>(in, a);
  std::uint32_t tail[W];
  const std::uint32_t* b = nullptr;
  for (std::size_t k = 0; k < row.end; k += W) {
    const bool full = simd::block_of<W>(row.inside, k, row.end, b, tail);
    Block<S, D, Groups> p{NeighbourFields<S, Groups>(in, b), V::zero(), S{}, V::zero()};
    p.x_ab = in.image(x_a - p.b.template vec<D>(Record<D>::x));
    const S q = simd::sqrt(p.x_ab.squaredNorm()) * in.inv_h;
    p.F = in.grad_scale * K::unit_f_over_r(q, 1.0 / q);
    if (!full) p.F = simd::first_lanes<S>(row.end - k) ? p.F : S{};
    p.grad_w = p.F * p.x_ab;
    pair_terms(p);
  }
}

// <grad rho>^L_a of Antuono et al. (2010), eq. (12) (renormalised_gradient.hpp).
template <class S, int D, class K>
inline Vec<D> density_gradient_row(const RowInput<D>& in, std::size_t a, InsideRow row) {
  using R = Record<D>;
  constexpr int groups = R::groups_of(R::volume + 1);
  RenormalisedGradient<D, S> g;
  const S rho_a = simd::broadcast<S>(in.record(a)[R::rho]);
  for_each_block<S, D, K, groups>(in, a, row, [&](const Block<S, D, groups>& p) {
    g.add(p.b[R::volume], rho_a, p.b[R::rho], p.x_ab, p.grad_w);
  });
  return g.summed().finish();
}

template <class S, int D, class K>
inline ForceRow<D> force_row(const RowInput<D>& in, std::size_t a, InsideRow row) {
  using V = simd::LaneVec<S, D>;
  using R = Record<D>;
  constexpr int groups = R::size / 4;
  auto lanes = [](Real x) { return simd::broadcast<S>(x); };
  const Real* rec_a = in.record(a);
  const S m = lanes(in.mass), alpha = lanes(in.alpha), h = lanes(in.h);
  const S rho_a = lanes(rec_a[R::rho]), p_a = lanes(rec_a[R::p_over_rho2]), q_a = lanes(rec_a[R::q_psi]);
  const S c_a = lanes(rec_a[R::sound_speed]);
  const V v_a = V::broadcast(Eigen::Map<const Vec<D>>(rec_a + R::v));
  const V grad_rho_a = V::broadcast(Eigen::Map<const Vec<D>>(rec_a + R::grad_rho));
  V acc = V::zero();
  S continuity{}, diffusion{};
  for_each_block<S, D, K, groups>(in, a, row, [&](const Block<S, D, groups>& p) {
    const V v_ab = v_a - p.b.template vec<D>(R::v);
    // seed 000, eq. (36): the summand of the difference divergence of v, which is also that of
    // the continuity equation (28) (sign of (36)): m v_ab . grad_a W_ab
    continuity += continuity_term<D>(m, v_ab, p.grad_w);
    if (in.cleaning) acc -= symmetric_gradient_term(m, q_a, p.grad_w, p.b[R::q_psi], p.grad_w);  // eq. (39)
    if (in.subsystem) return;
    acc += pressure_acceleration_term<D>(m, p_a, p.b[R::p_over_rho2], p.grad_w);  // eq. (27)
    const S rho_b = p.b[R::rho];
    if (in.viscosity) {
      const S c_ab = 0.5 * (c_a + p.b[R::sound_speed]);
      acc += monaghan_viscosity_term<D>(m, alpha, c_ab, 0.5 * (rho_a + rho_b), h, p.x_ab, v_ab, p.grad_w);
    }
    if (in.diffusion) {
      const S volume_b = p.b[R::volume];
      diffusion += in.corrected ? density_diffusion_term_radial(volume_b, rho_a, rho_b, grad_rho_a,
                                                                p.b.template vec<D>(R::grad_rho), p.F, p.grad_w)
                                : density_diffusion_term_radial(volume_b, rho_a, rho_b, p.F);
    }
  });
  return {acc.sum(), simd::sum(continuity), simd::sum(diffusion)};
}

// The AVX2 + FMA and AVX-512VL rows (wcsph_pair_rows_avx2.cpp): call only when the CPU has them.
template <int D>
std::size_t neighbours_inside_avx2(const RowInput<D>& in, std::size_t a, std::uint32_t* inside);
template <int D, class K>
Vec<D> density_gradient_row_avx2(const RowInput<D>& in, std::size_t a, InsideRow row);
template <int D, class K>
ForceRow<D> force_row_avx2(const RowInput<D>& in, std::size_t a, InsideRow row);
template <int D>
std::size_t neighbours_inside_avx512(const RowInput<D>& in, std::size_t a, std::uint32_t* inside);
template <int D, class K>
Vec<D> density_gradient_row_avx512(const RowInput<D>& in, std::size_t a, InsideRow row);
template <int D, class K>
ForceRow<D> force_row_avx512(const RowInput<D>& in, std::size_t a, InsideRow row);

}  // namespace sphark::wcsph_detail

#pragma GCC diagnostic pop
