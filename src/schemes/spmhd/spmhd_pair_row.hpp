#pragma once
// The SPMHD pair loop (seed 000, §II) for one particle a, in lanes of W neighbours
// (simd/lanes.hpp): S = Real is the scalar path, simd::Real2 the SSE2 path, simd::Real4 the
// AVX2 + FMA (or AVX-512VL) path (spmhd_rows_avx2.cpp; chosen at run time, simd/dispatch.hpp). The pair terms
// are the operators of sphark/operators/, each citing its equation, written once for every width.
//
// The row is first compacted to the interacting neighbours (|x_ab| < support max(h_a, h_b),
// x_ab != 0) in list order (rows are sorted by particle number), then taken W at a time; every
// lane gathers its neighbour's record (the fields a neighbour reads, in groups of four doubles:
// one load per group and lane, then a transpose) and sums its share; the lanes are added at the
// end in a fixed order. The lanes a row falls into depend only on its interacting neighbours:
// the result does not depend on the thread count, the slots or the Verlet skin.
#include <cstddef>
#include <cstdint>

#include "sphark/core/types.hpp"
#include "sphark/neighbours/periodic_box.hpp"
#include "sphark/operators/conjugate_cleaning.hpp"
#include "sphark/operators/mhd_operators.hpp"
#include "sphark/operators/pair_geometry.hpp"
#include "sphark/operators/pressure_force.hpp"
#include "sphark/operators/signal_velocity_dissipation.hpp"
#include "sphark/simd/lane_blocks.hpp"
#include "sphark/simd/lanes.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // lane-valued lambdas, inlined into their rows

namespace sphark::spmhd_detail {

using mhd::Vec3;

// Particle i's record: what its neighbours read, Record<D>::size doubles from records + size i.
// psi_o = psi/(Omega rho^2) (times c_h,i with local c_h), bo = (B/(Omega rho^2)) of the first D
// components, stress = M/(Omega rho^2), D x D (seed 000, eq. (8)).
template <int D>
struct Record {
  static constexpr int x = 0, h = D, m = D + 1, inv_h = D + 2, grad_scale = D + 3, rho = D + 4, P = D + 5, u = D + 6,
                       fast_speed = D + 7, psi_o = D + 8, psi = D + 9, B = D + 10, v = D + 13, stress = 2 * D + 13,
                       bo = 2 * D + 13 + D * D;
  static constexpr int size = (3 * D + 13 + D * D + 3) / 4 * 4;
};

// What the pair loop reads besides the records: the lists, the options.
template <int D>
struct RowInput {
  const Real* records;
  const std::uint32_t* indices;
  const std::size_t* offsets;
  MinimumImage<D> image;
  Real support;
  bool evolve;
  bool energy;  // u in the state (not with a barotropic EOS): without it no du/dt terms are summed
  bool induction, cleaning, constrained;
  Real alpha_visc, beta_visc, alpha_u, alpha_b;
  const Real* record(std::size_t i) const { return records + Record<D>::size * i; }
};

// The sums of one particle a (finish_particle turns them into derivatives).
template <int D>
struct PairSums {
  Vec<D> dv_dt = Vec<D>::Zero();     // (6) and viscosity; (9) subtracted at finish
  Vec<D> grad_psi = Vec<D>::Zero();  // (23), or the difference gradient
  mhd::Induction<D> induction;       // (7)
  Vec3 resistive = Vec3::Zero();     // (10)
  Real monopole = 0;                 // (9)
  Real div_b = 0;                    // (20)
  Real continuity = 0;               // sum_b m_b v_ab . g_a: div v (25) and the P dV work
  Real du_dt_dissipation = 0;        // heating of viscosity, conductivity and resistivity
  std::size_t pairs = 0;             // interacting neighbours
};

// The first `fields` fields of W neighbours' records, as lanes.
template <class S, int D, int Fields>
struct NeighbourFields : simd::GatheredFields<S, (Fields + 3) / 4> {
  NeighbourFields(const RowInput<D>& in, const std::uint32_t* b)
      : simd::GatheredFields<S, (Fields + 3) / 4>(in.records, Record<D>::size, b) {}
  simd::LaneMat<S, D> mat(int k) const {
    simd::LaneMat<S, D> M;
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) M.m[i][j] = this->f[k + D * i + j];
    return M;
  }
};

// Particle a's interacting neighbours in list order into inside (room: the row plus W); their number.
template <class S, int D>
inline std::size_t interacting_neighbours(const RowInput<D>& in, std::size_t a, std::uint32_t* inside) {
  using R = Record<D>;
  constexpr int W = simd::width<S>;
  const Real* rec_a = in.record(a);
  const auto x_a = simd::LaneVec<S, D>::broadcast(Eigen::Map<const Vec<D>>(rec_a + R::x));
  const S h_a = simd::broadcast<S>(rec_a[R::h]);
  const std::size_t end = in.offsets[a + 1];
  std::uint32_t tail[W];
  const std::uint32_t* b = nullptr;
  std::size_t n = 0;
  for (std::size_t k = in.offsets[a]; k < end; k += W) {
    const bool full = simd::block_of<W>(in.indices, k, end, b, tail);
    const NeighbourFields<S, D, R::h + 1> fb(in, b);
    const S r2 = in.image(x_a - fb.template vec<D>(R::x)).squaredNorm();
    const S reach = in.support * simd::max(h_a, fb[R::h]);
    auto close = (r2 < reach * reach) & (r2 != S{});
    if (!full) close = close & simd::first_lanes<S>(end - k);
    n = simd::append_lanes<W>(simd::mask_bits(close), b, inside, n);
  }
  return n;
}

// Particle a's quantities, as lanes.
template <class S, int D>
struct ParticleA {
  S h, inv_h, grad_scale, rho, P, u, fast_speed, psi_o, psi;
  simd::LaneVec<S, 3> B;
  simd::LaneVec<S, D> v, bo;
  simd::LaneMat<S, D> stress;
  explicit ParticleA(const Real* r) {
    using R = Record<D>;
    auto lanes = [](Real x) { return simd::broadcast<S>(x); };
    h = lanes(r[R::h]), inv_h = lanes(r[R::inv_h]), grad_scale = lanes(r[R::grad_scale]), rho = lanes(r[R::rho]);
    P = lanes(r[R::P]), u = lanes(r[R::u]), fast_speed = lanes(r[R::fast_speed]);
    psi_o = lanes(r[R::psi_o]), psi = lanes(r[R::psi]);
    for (int k = 0; k < 3; ++k) B[k] = lanes(r[R::B + k]);
    for (int k = 0; k < D; ++k) v[k] = lanes(r[R::v + k]), bo[k] = lanes(r[R::bo + k]);
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) stress.m[i][j] = lanes(r[R::stress + D * i + j]);
  }
};

// The sums of particle a, as lanes.
template <class S, int D>
struct LaneSums {
  using VD = simd::LaneVec<S, D>;
  using V3 = simd::LaneVec<S, 3>;
  VD dv_dt = VD::zero(), grad_psi = VD::zero();
  mhd::Induction<D, S> induction;
  V3 resistive = V3::zero();
  S monopole{}, div_b{}, continuity{}, du_dt_dissipation{};

  PairSums<D> summed(std::size_t pairs) const {
    PairSums<D> s;
    s.dv_dt = dv_dt.sum(), s.grad_psi = grad_psi.sum(), s.induction.sum = induction.summed(), s.resistive = resistive.sum();
    s.monopole = simd::sum(monopole), s.div_b = simd::sum(div_b), s.continuity = simd::sum(continuity);
    s.du_dt_dissipation = simd::sum(du_dt_dissipation);
    s.pairs = pairs;
    return s;
  }
};

// pair: the terms of W neighbours b of particle a (lanes past the row: F_a = F_b = 0, exact zeros).
template <class S, int D, class K>
inline void add_pairs(LaneSums<S, D>& s, const ParticleA<S, D>& pa, const RowInput<D>& in,
                      const NeighbourFields<S, D, Record<D>::size>& fb, const simd::LaneVec<S, D>& x_ab, bool full,
                      std::size_t valid) {
  using R = Record<D>;
  using VD = simd::LaneVec<S, D>;
  using V3 = simd::LaneVec<S, 3>;
  const S r = simd::sqrt(x_ab.squaredNorm()), inv_r = 1.0 / r;
  // grad_a W_ab(h_a) = F_a x_ab, grad_a W_ab(h_b) = F_b x_ab
  S F_a = pa.grad_scale * K::unit_f_over_r(r * pa.inv_h, pa.h * inv_r);
  S F_b = fb[R::grad_scale] * K::unit_f_over_r(r * fb[R::inv_h], fb[R::h] * inv_r);
  if (!full) {
    const auto inside = simd::first_lanes<S>(valid);
    F_a = inside ? F_a : S{}, F_b = inside ? F_b : S{};
  }
  const VD g_a = F_a * x_ab, g_b = F_b * x_ab;
  const S m_b = fb[R::m];
  const V3 B_b = fb.template vec<3>(R::B), B_ab = pa.B - B_b;

  s.div_b += difference_divergence_term(m_b, simd::head<D>(pa.B), simd::head<D>(B_b), g_a);  // eq. (20)
  if (in.cleaning) {
    if (in.constrained)  // eq. (23), the conjugate of (20)
      s.grad_psi += symmetric_gradient_term(m_b, pa.psi_o, RadialGradient<D, S, VD>{F_a, x_ab}, fb[R::psi_o],
                                            RadialGradient<D, S, VD>{F_b, x_ab})
                        .vector();
    else
      s.grad_psi += difference_gradient_term(m_b, pa.psi, fb[R::psi], g_a);
  }
  if (!in.evolve) return;

  const VD v_ab = pa.v - fb.template vec<D>(R::v);
  s.dv_dt += mhd::maxwell_force_term(m_b, pa.stress, g_a, fb.mat(R::stress), g_b);        // eq. (6)
  s.monopole += mhd::monopole_term(m_b, pa.bo, g_a, fb.template vec<D>(R::bo), g_b);      // eq. (9)
  s.continuity += continuity_term<D>(m_b, v_ab, g_a);                                     // eq. (25)
  if (in.induction) s.induction.pair(m_b, v_ab, pa.B, g_a);                               // eq. (7)

  // Dissipation with the mean kernel gradient gbar = (g_a + g_b)/2: rhat . gbar = (F_a + F_b) r / 2.
  const VD rhat = inv_r * x_ab;
  const S rhat_dot_gbar = 0.5 * (F_a + F_b) * r;
  const S rho_b = fb[R::rho], inv_rho_ab = 1.0 / (0.5 * (pa.rho + rho_b));
  const S w_ab = v_ab.dot(rhat);
  if (in.alpha_visc > 0) {
    const auto closing = approaching(w_ab);
    const auto visc = signal_velocity_viscosity_term<D>(m_b, simd::broadcast<S>(in.alpha_visc),
                                                        simd::broadcast<S>(in.beta_visc), pa.fast_speed,
                                                        fb[R::fast_speed], w_ab, inv_rho_ab, rhat, rhat_dot_gbar);
    s.dv_dt += simd::where(closing, visc.dv_dt);
    if (in.energy) s.du_dt_dissipation += closing ? visc.du_dt : S{};
  }
  if (in.alpha_u > 0)
    s.du_dt_dissipation += conductivity_term(m_b, simd::broadcast<S>(in.alpha_u), pa.P, fb[R::P], pa.u, fb[R::u],
                                             inv_rho_ab, rhat_dot_gbar);
  if (in.alpha_b > 0) {  // eq. (10)
    const auto res = mhd::resistivity_term<D>(m_b, simd::broadcast<S>(in.alpha_b), v_ab, w_ab, rhat, inv_rho_ab, B_ab,
                                              rhat_dot_gbar);
    s.resistive += res.dB_dt;
    if (in.energy) s.du_dt_dissipation += res.du_dt;
  }
}

// init, pair, and the lanes' sums of particle a; inside: room for a's row plus W.
template <class S, int D, class K>
inline PairSums<D> pair_row(const RowInput<D>& in, std::size_t a, std::uint32_t* inside) {
  using R = Record<D>;
  constexpr int W = simd::width<S>;
  const std::size_t n = interacting_neighbours<S, D>(in, a, inside);
  const ParticleA<S, D> pa(in.record(a));
  const auto x_a = simd::LaneVec<S, D>::broadcast(Eigen::Map<const Vec<D>>(in.record(a) + R::x));
  LaneSums<S, D> sums;
  std::uint32_t tail[W];
  const std::uint32_t* b = nullptr;
  for (std::size_t k = 0; k < n; k += W) {
    const bool full = simd::block_of<W>(inside, k, n, b, tail);
    const NeighbourFields<S, D, R::size> fb(in, b);
    add_pairs<S, D, K>(sums, pa, in, fb, in.image(x_a - fb.template vec<D>(R::x)), full, n - k);
  }
  return sums.summed(n);
}

// (spmhd_rows_avx2.cpp) Call only when the CPU has AVX2 and FMA, or AVX-512.
template <int D, class K>
PairSums<D> pair_row_avx2(const RowInput<D>& in, std::size_t a, std::uint32_t* inside);
template <int D, class K>
PairSums<D> pair_row_avx512(const RowInput<D>& in, std::size_t a, std::uint32_t* inside);

}  // namespace sphark::spmhd_detail

#pragma GCC diagnostic pop
