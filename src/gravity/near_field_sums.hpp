#pragma once
// The inner loops of the tree's near field, two pairs at a time with SSE2 (std::sqrt in a plain
// loop does not vectorise while it may set errno; the piecewise softening branches would
// mispredict), with scalar code for an odd last pair and for targets without SSE2:
//   add_newtonian_runs  f += sum_b m_b (x_a - x_b) / r^3,  p += sum_b m_b / r  over runs of
//                       particles; in masked runs the pairs with r < support * max(h_a, h_b)
//                       are left out and listed (b = self is left out and not listed);
//                       on CPUs with AVX2 and FMA four lanes (near_field_avx2.cpp);
//   add_softened_list   the softened pair interaction (kernel_softening.hpp) over such a list
//                       (four lanes with AVX2: softened_avx2.cpp).
// The order of the sums is fixed by the runs or the list alone (on a given CPU).
#include <array>
#include <cmath>
#include <cstdint>

#include "sphark/core/types.hpp"
#include "sphark/gravity/gravity_tree.hpp"
#include "sphark/gravity/kernel_softening.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include "simd_dispatch.hpp"

namespace sphark::gravity_detail {

struct ParticleArrays {
  const Real *x, *y, *z, *m, *h, *h_inv;
};

struct NewtonianSums {
  Real fx = 0, fy = 0, fz = 0, pot = 0;
};

#if defined(__SSE2__)
struct PairGravity2 {
  __m128d force_over_r, phi;
};
#endif

// One pair, scalar; returns false (and adds nothing) for a pair inside a softening reach.
inline bool add_newtonian_pair(const ParticleArrays& p, std::uint32_t b, const Real xa[3], Real reach_a, Real support,
                               NewtonianSums& s) {
  const Real dx = xa[0] - p.x[b], dy = xa[1] - p.y[b], dz = xa[2] - p.z[b];
  const Real r2 = dx * dx + dy * dy + dz * dz;
  if (support > 0) {
    const Real reach = reach_a > support * p.h[b] ? reach_a : support * p.h[b];
    if (r2 < reach * reach) return false;
  }
  const Real inv_r = 1 / std::sqrt(r2), m_r = p.m[b] * inv_r, c = m_r * inv_r * inv_r;
  s.fx += c * dx, s.fy += c * dy, s.fz += c * dz, s.pot += m_r;
  return true;
}

// Appends b + l for every set bit l of `lanes` (up to 4 lanes) except b + l = self to inside,
// without branching on the bits: four slots are always written (inside needs 4 spare slots).
inline std::uint32_t list_inside(unsigned lanes, std::uint32_t b, std::uint32_t self, std::uint32_t* inside,
                                 std::uint32_t n) {
  static constexpr std::uint8_t kOffsets[16][4] = {{0, 0, 0, 0}, {0, 0, 0, 0}, {1, 0, 0, 0}, {0, 1, 0, 0},
                                                   {2, 0, 0, 0}, {0, 2, 0, 0}, {1, 2, 0, 0}, {0, 1, 2, 0},
                                                   {3, 0, 0, 0}, {0, 3, 0, 0}, {1, 3, 0, 0}, {0, 1, 3, 0},
                                                   {2, 3, 0, 0}, {0, 2, 3, 0}, {1, 2, 3, 0}, {0, 1, 2, 3}};
  static constexpr std::uint8_t kCount[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};
  if (self - b < 4) lanes &= ~(1u << (self - b));
  for (int l = 0; l < 4; ++l) inside[n + l] = b + kOffsets[lanes][l];
  return n + kCount[lanes];
}

#if defined(SPHARK_GRAVITY_HAVE_AVX2)
std::uint32_t add_newtonian_runs_avx2(const ParticleArrays& p, const ParticleRun* runs, std::uint32_t n_newtonian,
                                      std::uint32_t n_runs, const Real xa[3], Real reach_a, Real support,
                                      std::uint32_t self, NewtonianSums& s, std::uint32_t* inside);
template <class K>  // softened_avx2.cpp
void add_softened_list_avx2(const ParticleArrays& p, const std::uint32_t* inside, std::uint32_t n, const Real xa[3],
                            Real ha, Real ha_inv, NewtonianSums& s);
#endif

#if defined(__SSE2__)
inline Real lane_sum(__m128d v) { return _mm_cvtsd_f64(v) + _mm_cvtsd_f64(_mm_unpackhi_pd(v, v)); }

// One run on two lanes into acc (fx, fy, fz, pot); Masked: pairs inside a reach listed instead.
template <bool Masked>
inline void newtonian_run_sse2(const ParticleArrays& p, ParticleRun run, const Real xa[3], Real reach_a,
                               Real support, std::uint32_t self, __m128d acc[4], NewtonianSums& s,
                               std::uint32_t* inside, std::uint32_t& n_inside) {
  const __m128d X = _mm_set1_pd(xa[0]), Y = _mm_set1_pd(xa[1]), Z = _mm_set1_pd(xa[2]), one = _mm_set1_pd(1);
  std::uint32_t b = run.begin;
  for (; b + 2 <= run.end; b += 2) {
    const __m128d dx = X - _mm_loadu_pd(p.x + b), dy = Y - _mm_loadu_pd(p.y + b), dz = Z - _mm_loadu_pd(p.z + b);
    __m128d r2 = dx * dx + dy * dy + dz * dz, m = _mm_loadu_pd(p.m + b);
    if constexpr (Masked) {
      const __m128d reach = _mm_max_pd(_mm_set1_pd(reach_a), _mm_set1_pd(support) * _mm_loadu_pd(p.h + b));
      __m128d outside = _mm_cmpge_pd(r2, reach * reach);
      if (self - b < 2)  // never count a particle with itself (h = 0 gives it no reach)
        outside = _mm_and_pd(outside, _mm_castsi128_pd(_mm_set_epi64x(self == b + 1 ? 0 : -1, self == b ? 0 : -1)));
      n_inside = list_inside(0x3 & ~_mm_movemask_pd(outside), b, self, inside, n_inside);
      m = _mm_and_pd(outside, m);
      r2 = _mm_or_pd(_mm_and_pd(outside, r2), _mm_andnot_pd(outside, one));
    }
    const __m128d inv_r = one / _mm_sqrt_pd(r2), m_r = m * inv_r, c = m_r * inv_r * inv_r;
    acc[0] += c * dx, acc[1] += c * dy, acc[2] += c * dz, acc[3] += m_r;
  }
  if (b < run.end && b != self && !add_newtonian_pair(p, b, xa, reach_a, Masked ? support : 0, s))
    inside[n_inside++] = b;
}
#endif

// The Newtonian near field of one particle over its runs: runs[0 .. n_newtonian) have no pair
// inside a softening; in runs[n_newtonian .. n_runs) the pairs inside a reach
// (r < support * max(h_a, h_b)) are left out and listed in inside (capacity: the particles of
// those runs, plus 4; b = self neither added nor listed). Returns how many were listed.
inline std::uint32_t add_newtonian_runs(const ParticleArrays& p, const ParticleRun* runs, std::uint32_t n_newtonian,
                                        std::uint32_t n_runs, const Real xa[3], Real reach_a, Real support,
                                        std::uint32_t self, NewtonianSums& s, std::uint32_t* inside) {
#if defined(SPHARK_GRAVITY_HAVE_AVX2)
  if (cpu_has_avx2_fma())
    return add_newtonian_runs_avx2(p, runs, n_newtonian, n_runs, xa, reach_a, support, self, s, inside);
#endif
  std::uint32_t n_inside = 0;
#if defined(__SSE2__)
  __m128d acc[4] = {_mm_setzero_pd(), _mm_setzero_pd(), _mm_setzero_pd(), _mm_setzero_pd()};
  for (std::uint32_t k = 0; k < n_newtonian; ++k)
    newtonian_run_sse2<false>(p, runs[k], xa, reach_a, support, self, acc, s, inside, n_inside);
  for (std::uint32_t k = n_newtonian; k < n_runs; ++k)
    newtonian_run_sse2<true>(p, runs[k], xa, reach_a, support, self, acc, s, inside, n_inside);
  s.fx += lane_sum(acc[0]), s.fy += lane_sum(acc[1]), s.fz += lane_sum(acc[2]), s.pot += lane_sum(acc[3]);
#else
  for (std::uint32_t k = 0; k < n_runs; ++k)
    for (std::uint32_t b = runs[k].begin; b < runs[k].end; ++b)
      if (b != self && !add_newtonian_pair(p, b, xa, reach_a, k < n_newtonian ? 0 : support, s)) inside[n_inside++] = b;
#endif
  return n_inside;
}

#if defined(__SSE2__)
inline __m128d select(__m128d mask, __m128d a, __m128d b) { return _mm_or_pd(_mm_and_pd(mask, a), _mm_andnot_pd(mask, b)); }

template <int N>
inline __m128d horner(const std::array<Real, softening_detail::kMaxTerms>& c, __m128d q) {
  __m128d s = _mm_set1_pd(c[N - 1]);
  for (int j = N - 2; j >= 0; --j) s = s * q + _mm_set1_pd(c[j]);
  return s;
}

// one_side (kernel_softening.hpp) for two lanes, the piece chosen by masks; r = 0 is fine
// (the A_k / r terms are masked out on the innermost piece).
template <class K>
inline PairGravity2 one_side(__m128d r, __m128d inv_r, __m128d h, __m128d h_inv) {
  using Table = softening_detail::SofteningTable<K>;
  const __m128d q = r * h_inv, q2 = q * q;
  __m128d f = _mm_setzero_pd(), v = f, a = f, outer = f;
  for (int k = 0; k < Table::count; ++k) {
    const softening_detail::SofteningPiece& pc = Table::pieces[k];
    const __m128d fk = horner<Table::n_terms>(pc.force.c, q);
    const __m128d vk = _mm_set1_pd(pc.pot_const) + q2 * horner<Table::n_terms>(pc.potential.c, q);
    if (k == 0) {
      f = fk, v = vk, a = _mm_set1_pd(pc.mass_const);
      continue;
    }
    const __m128d in = _mm_cmpge_pd(q, _mm_set1_pd(Table::pieces[k - 1].end));
    f = select(in, fk, f), v = select(in, vk, v), a = select(in, _mm_set1_pd(pc.mass_const), a);
    outer = _mm_or_pd(outer, in);
  }
  const __m128d h_inv3 = h_inv * h_inv * h_inv, ir3 = inv_r * inv_r * inv_r;
  const __m128d inside_f = f * h_inv3 + _mm_and_pd(outer, a * ir3), inside_v = v * h_inv - _mm_and_pd(outer, a * inv_r);
  const __m128d out = _mm_cmpge_pd(r, _mm_set1_pd(K::support) * h);
  return {select(out, ir3, inside_f), select(out, _mm_setzero_pd() - inv_r, inside_v)};
}
#endif

// Adds the softened pairs of a with inside[0 .. n) to s (as add_newtonian_run: sum m f_ab x_ab
// and sum m phi_ab). inside[n .. n + 4) must be readable (the AVX2 loop loads four at a time).
template <class K>
inline void add_softened_list(const ParticleArrays& p, const std::uint32_t* inside, std::uint32_t n, const Real xa[3],
                              Real ha, Real ha_inv, NewtonianSums& s) {
#if defined(SPHARK_GRAVITY_HAVE_AVX2)
  if (cpu_has_avx2_fma()) return add_softened_list_avx2<K>(p, inside, n, xa, ha, ha_inv, s);
#endif
  std::uint32_t k = 0;
#if defined(__SSE2__)
  const __m128d X = _mm_set1_pd(xa[0]), Y = _mm_set1_pd(xa[1]), Z = _mm_set1_pd(xa[2]), half = _mm_set1_pd(0.5);
  const __m128d Ha = _mm_set1_pd(ha), Ha_inv = _mm_set1_pd(ha_inv), one = _mm_set1_pd(1);
  __m128d fx = _mm_setzero_pd(), fy = fx, fz = fx, pot = fx;
  for (; k + 2 <= n; k += 2) {
    const std::uint32_t b0 = inside[k], b1 = inside[k + 1];
    const __m128d dx = X - _mm_set_pd(p.x[b1], p.x[b0]), dy = Y - _mm_set_pd(p.y[b1], p.y[b0]);
    const __m128d dz = Z - _mm_set_pd(p.z[b1], p.z[b0]);
    const __m128d r = _mm_sqrt_pd(dx * dx + dy * dy + dz * dz);
    const __m128d inv_r = select(_mm_cmpgt_pd(r, _mm_setzero_pd()), one / r, _mm_setzero_pd());
    const PairGravity2 sa = one_side<K>(r, inv_r, Ha, Ha_inv);
    const PairGravity2 sb = one_side<K>(r, inv_r, _mm_set_pd(p.h[b1], p.h[b0]), _mm_set_pd(p.h_inv[b1], p.h_inv[b0]));
    const __m128d m = _mm_set_pd(p.m[b1], p.m[b0]);
    const __m128d c = m * (half * (sa.force_over_r + sb.force_over_r));
    fx += c * dx, fy += c * dy, fz += c * dz, pot += m * (half * (sa.phi + sb.phi));
  }
  s.fx += lane_sum(fx), s.fy += lane_sum(fy), s.fz += lane_sum(fz), s.pot += lane_sum(pot);
#endif
  for (; k < n; ++k) {
    const std::uint32_t b = inside[k];
    const Real dx = xa[0] - p.x[b], dy = xa[1] - p.y[b], dz = xa[2] - p.z[b];
    const PairGravity g = softened_pair<K>(dx * dx + dy * dy + dz * dz, ha, ha_inv, p.h[b], p.h_inv[b]);
    const Real c = p.m[b] * g.force_over_r;
    s.fx += c * dx, s.fy += c * dy, s.fz += c * dz, s.pot += p.m[b] * g.phi;
  }
}

}  // namespace sphark::gravity_detail
