#pragma once
// Lanes: W pair interactions computed at once, for the pair loops' vector paths. A lane type S is
// Real (W = 1, the scalar path) or a GCC/Clang vector of W doubles (Real2: SSE2, the x86-64
// baseline; Real4: AVX2 or AVX-512VL, used only inside functions compiled for those instruction
// sets and chosen at run time, simd/dispatch.hpp). The arithmetic operators, comparisons (a mask per lane) and `m ? a : b`
// (select per lane) are the language's on every lane type, so a pair term written once with them
// serves every width; what the language lacks is here: broadcast, sqrt, min / max, positive
// part, horizontal sum, the gather of a neighbour field, and LaneVec<S, D> (a D-vector of lanes,
// the few operations the pair terms use on vectors, as Eigen's Vec<D> has them).
//
// No function here carries a target attribute, so that a template instantiated for Real4 outside
// an AVX2 function is ordinary (slow, correct) code with the caller's calling convention, never an
// error, an AVX2 instruction in a baseline function, nor a vector passed in a ymm register to a
// baseline caller: the AVX2 pair loops are flattened functions with target("avx2,fma"), and a
// build that does not flatten them (Debug, sanitizers) must get the same numbers.
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "sphark/core/types.hpp"

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // vector arguments of inline helpers (always inlined into their users)
#endif

namespace sphark::simd {

typedef double Real2 __attribute__((vector_size(16)));
typedef double Real4 __attribute__((vector_size(32)));

template <class S>
inline constexpr int width = 1;
template <>
inline constexpr int width<Real2> = 2;
template <>
inline constexpr int width<Real4> = 4;

template <class S>
inline S broadcast(Real x) {
  if constexpr (width<S> == 1) return x;
  else return S{} + x;
}

// Lane l holds l: 0, 1, ..., W - 1.
template <class S>
inline S lane_numbers() {
  if constexpr (width<S> == 1) {
    return 0;
  } else {
    S s{};
    for (int l = 0; l < width<S>; ++l) s[l] = l;
    return s;
  }
}

template <class S>
inline S min(S a, S b) { return b < a ? b : a; }  // as std::min
template <class S>
inline S max(S a, S b) { return a < b ? b : a; }  // as std::max
// max(x, 0), the clamp of the compactly supported kernel shapes
template <class S>
inline S positive_part(S x) { return max(x, S{}); }
template <class S>
inline S abs(S x) { return x < S{} ? -x : x; }

inline Real sqrt(Real x) { return std::sqrt(x); }
#if defined(__SSE2__)
inline Real2 sqrt(Real2 x) { return __builtin_ia32_sqrtpd(x); }
#else
inline Real2 sqrt(Real2 x) { return Real2{std::sqrt(x[0]), std::sqrt(x[1])}; }
#endif
// Four lanes as two halves of SSE2 (baseline) operations: no function here carries a target
// attribute, so a Real4 instantiation that the compiler leaves out of line (a Debug build does
// not flatten) passes its vectors by the same convention as its caller. Inlined into an AVX2
// function, each half is a VEX instruction (vsqrtpd, vmovmskpd on the halves).
inline Real2 low_half(Real4 x) { return __builtin_shufflevector(x, x, 0, 1); }
inline Real2 high_half(Real4 x) { return __builtin_shufflevector(x, x, 2, 3); }
inline Real4 sqrt(Real4 x) { return __builtin_shufflevector(sqrt(low_half(x)), sqrt(high_half(x)), 0, 1, 2, 3); }
#if defined(__GNUC__) && defined(__x86_64__)
#define SPHARK_SIMD_HAVE_AVX2 1
#endif

// Bit l set if lane l of a mask (a comparison's result) is set.
inline unsigned mask_bits(bool m) { return m; }
inline unsigned mask_bits(int m) { return m != 0; }
typedef long Mask2 __attribute__((vector_size(16)));
typedef long Mask4 __attribute__((vector_size(32)));
#if defined(__SSE2__)
inline unsigned mask_bits(Mask2 m) { return static_cast<unsigned>(__builtin_ia32_movmskpd(reinterpret_cast<Real2>(m))); }
#else
inline unsigned mask_bits(Mask2 m) { return (m[0] != 0) | (m[1] != 0) << 1; }
#endif
inline unsigned mask_bits(Mask4 m) {
  const Real4 d = reinterpret_cast<Real4>(m);
  return mask_bits(reinterpret_cast<Mask2>(low_half(d))) | mask_bits(reinterpret_cast<Mask2>(high_half(d))) << 2;
}

// For each mask of W lanes: its set lanes in order, and how many.
template <int W>
struct SetLanes {
  alignas(4 * W) std::uint32_t lane[1 << W][W] = {};
  std::uint8_t count[1 << W] = {};
  constexpr SetLanes() {
    for (unsigned bits = 0; bits < (1u << W); ++bits)
      for (int l = 0; l < W; ++l)
        if (bits >> l & 1) lane[bits][count[bits]++] = static_cast<std::uint32_t>(l);
  }
};
template <int W>
inline constexpr SetLanes<W> kSetLanes{};

// Appends the entries b[l] of the set lanes l (bits) to out[n ...) in lane order; returns the
// new n. Branch-free: always writes W entries (out needs W spare slots). Four lanes: one
// shuffle of the four indices by the mask's table row (one vpermilps with AVX).
template <int W>
inline std::size_t append_lanes(unsigned bits, const std::uint32_t* b, std::uint32_t* out, std::size_t n) {
  typedef std::uint32_t U4 __attribute__((vector_size(16)));
  typedef std::uint32_t U4u __attribute__((vector_size(16), aligned(4), may_alias));
  if constexpr (W == 4) {
    *reinterpret_cast<U4u*>(out + n) =
        __builtin_shuffle(*reinterpret_cast<const U4u*>(b), *reinterpret_cast<const U4*>(kSetLanes<4>.lane[bits]));
  } else {
    for (int l = 0; l < W; ++l) out[n + l] = b[kSetLanes<W>.lane[bits][l]];
  }
  return n + kSetLanes<W>.count[bits];
}

// Sum of the lanes, (l0 + l1) + (l2 + l3) for four: a fixed order.
inline Real sum(Real x) { return x; }
inline Real sum(Real2 x) { return x[0] + x[1]; }
inline Real sum(Real4 x) { return (x[0] + x[1]) + (x[2] + x[3]); }

// Lane l holds base[stride * index[l]]: a neighbour field for W neighbours.
template <class S>
inline S gather(const Real* base, const std::uint32_t* index, int stride) {
  if constexpr (width<S> == 1) {
    return base[static_cast<std::size_t>(stride) * index[0]];
  } else {
    S s;
    for (int l = 0; l < width<S>; ++l) s[l] = base[static_cast<std::size_t>(stride) * index[l]];
    return s;
  }
}

// Records: the fields of particle i that its neighbours read, stride doubles from records +
// stride * i, in groups of four (stride a multiple of 4). gather_group returns fields
// first .. first + 3 of W particles as four lane values: on four lanes, one load of each
// particle's group and a 4 x 4 transpose (8 shuffles) instead of 16 loads and 12 inserts.
template <class S>
struct Group {
  S f[4];
};
// W consecutive doubles at p (any 8-byte alignment) as one vector load.
template <class S>
inline S load(const Real* p) {
  if constexpr (width<S> == 1) {
    return *p;
  } else {
    typedef Real Unaligned __attribute__((vector_size(sizeof(S)), aligned(8), may_alias));
    return *reinterpret_cast<const Unaligned*>(p);
  }
}
template <class S>
inline Group<S> gather_group(const Real* records, int stride, const std::uint32_t* index, int first) {
  Group<S> g;
  if constexpr (width<S> == 4) {
    S r[4];
    for (int l = 0; l < 4; ++l) r[l] = load<S>(records + static_cast<std::size_t>(stride) * index[l] + first);
    const S t0 = __builtin_shuffle(r[0], r[1], Mask4{0, 4, 2, 6}), t1 = __builtin_shuffle(r[0], r[1], Mask4{1, 5, 3, 7});
    const S t2 = __builtin_shuffle(r[2], r[3], Mask4{0, 4, 2, 6}), t3 = __builtin_shuffle(r[2], r[3], Mask4{1, 5, 3, 7});
    g.f[0] = __builtin_shuffle(t0, t2, Mask4{0, 1, 4, 5});
    g.f[1] = __builtin_shuffle(t1, t3, Mask4{0, 1, 4, 5});
    g.f[2] = __builtin_shuffle(t0, t2, Mask4{2, 3, 6, 7});
    g.f[3] = __builtin_shuffle(t1, t3, Mask4{2, 3, 6, 7});
  } else if constexpr (width<S> == 2) {
    for (int half = 0; half < 2; ++half) {
      S r[2];
      for (int l = 0; l < 2; ++l) r[l] = load<S>(records + static_cast<std::size_t>(stride) * index[l] + first + 2 * half);
      g.f[2 * half] = __builtin_shuffle(r[0], r[1], Mask2{0, 2});
      g.f[2 * half + 1] = __builtin_shuffle(r[0], r[1], Mask2{1, 3});
    }
  } else {
    for (int k = 0; k < 4; ++k) g.f[k] = records[static_cast<std::size_t>(stride) * index[0] + first + k];
  }
  return g;
}

// A D-vector of lanes: component k holds W values (the pair terms' x_ab, v_ab, gradients).
template <class S, int D>
struct LaneVec {
  S c[D];

  static LaneVec zero() {
    LaneVec v;
    for (int k = 0; k < D; ++k) v.c[k] = S{};
    return v;
  }
  static LaneVec broadcast(const Vec<D>& x) {
    LaneVec v;
    for (int k = 0; k < D; ++k) v.c[k] = simd::broadcast<S>(x[k]);
    return v;
  }
  // component k of W neighbours stored D per particle
  static LaneVec gather(const Real* base, const std::uint32_t* index) {
    LaneVec v;
    for (int k = 0; k < D; ++k) v.c[k] = simd::gather<S>(base + k, index, D);
    return v;
  }
  S& operator[](int k) { return c[k]; }
  const S& operator[](int k) const { return c[k]; }
  S dot(const LaneVec& o) const {
    S s = c[0] * o.c[0];
    for (int k = 1; k < D; ++k) s += c[k] * o.c[k];
    return s;
  }
  S squaredNorm() const { return dot(*this); }
  S norm() const { return simd::sqrt(squaredNorm()); }
  static LaneVec Zero() { return zero(); }
  LaneVec& operator+=(const LaneVec& o) {
    for (int k = 0; k < D; ++k) c[k] += o.c[k];
    return *this;
  }
  LaneVec& operator-=(const LaneVec& o) {
    for (int k = 0; k < D; ++k) c[k] -= o.c[k];
    return *this;
  }
  // the sum of the lanes of each component
  Vec<D> sum() const {
    Vec<D> v;
    for (int k = 0; k < D; ++k) v[k] = simd::sum(c[k]);
    return v;
  }
};

template <class S, int D>
inline LaneVec<S, D> operator+(LaneVec<S, D> a, const LaneVec<S, D>& b) { return a += b; }
template <class S, int D>
inline LaneVec<S, D> operator-(LaneVec<S, D> a, const LaneVec<S, D>& b) { return a -= b; }
template <class S, int D>
inline LaneVec<S, D> operator-(LaneVec<S, D> a) {
  for (int k = 0; k < D; ++k) a.c[k] = -a.c[k];
  return a;
}
template <class S, int D>
inline LaneVec<S, D> operator*(S s, LaneVec<S, D> a) {
  for (int k = 0; k < D; ++k) a.c[k] = s * a.c[k];
  return a;
}
template <class S, int D>
  requires(!std::is_same_v<S, Real>)
inline LaneVec<S, D> operator*(Real s, LaneVec<S, D> a) {
  for (int k = 0; k < D; ++k) a.c[k] = s * a.c[k];
  return a;
}
template <class S, int D>
inline LaneVec<S, D> operator*(LaneVec<S, D> a, S s) { return s * a; }

// Lanes where the mask is set, zero elsewhere.
template <class M, class S, int D>
inline LaneVec<S, D> where(const M& mask, LaneVec<S, D> v) {
  for (int k = 0; k < D; ++k) v.c[k] = mask ? v.c[k] : S{};
  return v;
}

// The first D components.
template <int D, class S, int N>
inline LaneVec<S, D> head(const LaneVec<S, N>& v) {
  LaneVec<S, D> h;
  for (int k = 0; k < D; ++k) h.c[k] = v.c[k];
  return h;
}

// A D x D matrix of lanes (the Maxwell stress of a pair loop), row-major.
template <class S, int D>
struct LaneMat {
  S m[D][D];
  LaneVec<S, D> operator*(const LaneVec<S, D>& g) const {
    LaneVec<S, D> r;
    for (int i = 0; i < D; ++i) {
      r.c[i] = m[i][0] * g.c[0];
      for (int j = 1; j < D; ++j) r.c[i] += m[i][j] * g.c[j];
    }
    return r;
  }
};

// The scalar of a vector type: Eigen's Scalar, or a LaneVec's lane type.
template <class V>
struct ScalarOf {
  using type = typename V::Scalar;
};
template <class S, int D>
struct ScalarOf<LaneVec<S, D>> {
  using type = S;
};
template <class V>
using scalar_of = typename ScalarOf<V>::type;

// Eigen's Vec<N> for Real, LaneVec for lanes (sums that tests also read as vectors).
template <class S, int N>
using VecOf = std::conditional_t<std::is_same_v<S, Real>, Vec<N>, LaneVec<S, N>>;

}  // namespace sphark::simd

#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
