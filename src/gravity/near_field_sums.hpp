#pragma once
// The inner loops of the tree's near field, two pairs at a time with SSE2 (std::sqrt in a plain
// loop does not vectorise while it may set errno; the piecewise softening branches would
// mispredict), with scalar code for an odd last pair and for targets without SSE2:
//   add_newtonian_run   f += sum_b m_b (x_a - x_b) / r^3,  p += sum_b m_b / r  over a run of
//                       particles; with a softening reach (support > 0) the pairs with
//                       r < support * max(h_a, h_b) are left out and listed in `inside`
//                       (b = self is left out and not listed);
//   add_softened_list   the softened pair interaction (kernel_softening.hpp) over such a list.
// The order of the sums is fixed by the run or list alone.
#include <array>
#include <cmath>
#include <cstdint>

#include "sphark/core/types.hpp"
#include "sphark/gravity/kernel_softening.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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

// Adds the run [b0, b1) to s; returns how many slots it wrote to inside (support > 0 only).
inline std::uint32_t add_newtonian_run(const ParticleArrays& p, std::uint32_t b0, std::uint32_t b1, const Real xa[3],
                                       Real reach_a, Real support, std::uint32_t self, NewtonianSums& s,
                                       std::uint32_t* inside) {
  std::uint32_t n_inside = 0, b = b0;
#if defined(__SSE2__)
  const __m128d X = _mm_set1_pd(xa[0]), Y = _mm_set1_pd(xa[1]), Z = _mm_set1_pd(xa[2]), one = _mm_set1_pd(1);
  const __m128d S = _mm_set1_pd(support), RA = _mm_set1_pd(reach_a);
  __m128d fx = _mm_setzero_pd(), fy = fx, fz = fx, pot = fx;
  for (; b + 2 <= b1; b += 2) {
    const __m128d dx = X - _mm_loadu_pd(p.x + b), dy = Y - _mm_loadu_pd(p.y + b), dz = Z - _mm_loadu_pd(p.z + b);
    __m128d r2 = dx * dx + dy * dy + dz * dz, m = _mm_loadu_pd(p.m + b);
    if (support > 0) {
      const __m128d reach = _mm_max_pd(RA, S * _mm_loadu_pd(p.h + b));
      const __m128d outside = _mm_cmpge_pd(r2, reach * reach);
      const int bits = _mm_movemask_pd(outside);
      if (!(bits & 1) && b != self) inside[n_inside++] = b;
      if (!(bits & 2) && b + 1 != self) inside[n_inside++] = b + 1;
      m = _mm_and_pd(outside, m);
      r2 = _mm_or_pd(_mm_and_pd(outside, r2), _mm_andnot_pd(outside, one));
    }
    const __m128d inv_r = one / _mm_sqrt_pd(r2), m_r = m * inv_r, c = m_r * inv_r * inv_r;
    fx += c * dx, fy += c * dy, fz += c * dz, pot += m_r;
  }
  alignas(16) Real lanes[4][2];
  _mm_store_pd(lanes[0], fx), _mm_store_pd(lanes[1], fy), _mm_store_pd(lanes[2], fz), _mm_store_pd(lanes[3], pot);
  s.fx += lanes[0][0] + lanes[0][1], s.fy += lanes[1][0] + lanes[1][1];
  s.fz += lanes[2][0] + lanes[2][1], s.pot += lanes[3][0] + lanes[3][1];
#endif
  for (; b < b1; ++b)
    if (!add_newtonian_pair(p, b, xa, reach_a, support, s) && b != self) inside[n_inside++] = b;
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
// and sum m phi_ab).
template <class K>
inline void add_softened_list(const ParticleArrays& p, const std::uint32_t* inside, std::uint32_t n, const Real xa[3],
                              Real ha, Real ha_inv, NewtonianSums& s) {
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
  alignas(16) Real lanes[4][2];
  _mm_store_pd(lanes[0], fx), _mm_store_pd(lanes[1], fy), _mm_store_pd(lanes[2], fz), _mm_store_pd(lanes[3], pot);
  s.fx += lanes[0][0] + lanes[0][1], s.fy += lanes[1][0] + lanes[1][1];
  s.fz += lanes[2][0] + lanes[2][1], s.pot += lanes[3][0] + lanes[3][1];
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
