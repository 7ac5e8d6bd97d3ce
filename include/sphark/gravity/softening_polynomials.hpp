#pragma once
// The 3D kernels of sphark/kernels/kernels.hpp as piecewise polynomials in q = r / h, and the
// softened-gravity polynomials derived from them at compile time (kernel_softening.hpp uses them).
//
// Every kernel shape f(q) (W = sigma / h^3 f(q)) is a polynomial on each of its pieces
// [b_k, b_{k+1}): sum_j c_j q^j. On that piece (Price & Monaghan 2007, MNRAS 374, 1347, §2:
// the softened potential of a particle is the potential of its mass distributed as W):
//   enclosed mass   mu(q)     = 4 pi sigma int_0^q f(s) s^2 ds       = A_k + sum_j a_j q^(j+3),
//                               a_j = 4 pi sigma c_j / (j+3),  A_k = mu(b_k) - sum_j a_j b_k^(j+3)
//   force           phi~'(q)  = mu(q) / q^2                          = A_k / q^2 + sum_j a_j q^(j+1)
//   potential       phi~(q)   = -int_q^inf phi~'(s) ds               = -A_k / q + B_k + sum_j a_j q^(j+2) / (j+2)
//   h-derivative    phi~ + q phi~'                                   = B_k + sum_j a_j (j+3)/(j+2) q^(j+2)
// with B_k fixed by continuity of phi~ at b_{k+1} (phi~(Q) = -1/Q at the support Q, mu(Q) = 1).
// A_0 = 0: the innermost piece has no 1/q terms. The 1/q terms cancel in phi~ + q phi~'.
#include <array>
#include <cstddef>

#include "sphark/core/types.hpp"
#include "sphark/kernels/kernels.hpp"

namespace sphark::softening_detail {

inline constexpr int kMaxTerms = 16;  // Wendland C6 in 3D: degree 11; its potential: degree 13

// sum_j c[j] q^j
struct Poly {
  std::array<Real, kMaxTerms> c{};
};

constexpr Poly constant(Real a) {
  Poly p;
  p.c[0] = a;
  return p;
}
constexpr Poly linear(Real a, Real b) {  // a + b q
  Poly p;
  p.c[0] = a;
  p.c[1] = b;
  return p;
}
constexpr Poly operator+(Poly p, const Poly& r) {
  for (int j = 0; j < kMaxTerms; ++j) p.c[j] += r.c[j];
  return p;
}
constexpr Poly operator*(Real s, Poly p) {
  for (Real& v : p.c) v *= s;
  return p;
}
constexpr Poly operator*(const Poly& p, const Poly& r) {
  Poly out;
  for (int i = 0; i < kMaxTerms; ++i)
    for (int j = 0; i + j < kMaxTerms; ++j) out.c[i + j] += p.c[i] * r.c[j];
  return out;
}
constexpr Poly power(const Poly& p, int n) {
  Poly out = constant(1);
  for (int i = 0; i < n; ++i) out = out * p;
  return out;
}
constexpr int degree(const Poly& p) {
  for (int j = kMaxTerms - 1; j > 0; --j)
    if (p.c[j] != 0) return j;
  return 0;
}
// Horner; N terms (N - 1 = the degree, a compile-time bound at the call sites).
template <int N>
inline constexpr Real horner(const std::array<Real, kMaxTerms>& c, Real q) {
  Real s = c[N - 1];
  for (int j = N - 2; j >= 0; --j) s = s * q + c[j];
  return s;
}

// The kernel shapes f(q) of kernels.hpp, piece by piece (3D). Pieces end at breaks[1..count].
template <class K>
struct KernelPieces;

template <>
struct KernelPieces<CubicSpline<3>> {  // Monaghan (2005), eq. (2.6)
  static constexpr int count = 2;
  static constexpr std::array<Real, 3> breaks{0, 1, 2};
  static constexpr std::array<Poly, 2> shapes() {
    Poly inner;
    inner.c[0] = 1, inner.c[2] = -1.5, inner.c[3] = 0.75;
    return {inner, 0.25 * power(linear(2, -1), 3)};
  }
};

template <>
struct KernelPieces<QuinticSpline<3>> {  // (3-q)^5 - 6 (2-q)^5 + 15 (1-q)^5, each term where positive
  static constexpr int count = 3;
  static constexpr std::array<Real, 4> breaks{0, 1, 2, 3};
  static constexpr std::array<Poly, 3> shapes() {
    const Poly t3 = power(linear(3, -1), 5), t2 = -6.0 * power(linear(2, -1), 5), t1 = 15.0 * power(linear(1, -1), 5);
    return {t3 + t2 + t1, t3 + t2, t3};
  }
};

// Wendland in 3D with t = q / 2 (Dehnen & Aly 2012, Table 1, H = 2h): one piece on [0, 2).
template <>
struct KernelPieces<WendlandC2<3>> {  // (1-t)^4 (1 + 4t)
  static constexpr int count = 1;
  static constexpr std::array<Real, 2> breaks{0, 2};
  static constexpr std::array<Poly, 1> shapes() { return {power(linear(1, -0.5), 4) * linear(1, 2)}; }
};

template <>
struct KernelPieces<WendlandC4<3>> {  // (1-t)^6 (1 + 6t + 35/3 t^2)
  static constexpr int count = 1;
  static constexpr std::array<Real, 2> breaks{0, 2};
  static constexpr std::array<Poly, 1> shapes() {
    Poly tail = linear(1, 3);
    tail.c[2] = 35.0 / 12.0;
    return {power(linear(1, -0.5), 6) * tail};
  }
};

template <>
struct KernelPieces<WendlandC6<3>> {  // (1-t)^8 (1 + 8t + 25t^2 + 32t^3)
  static constexpr int count = 1;
  static constexpr std::array<Real, 2> breaks{0, 2};
  static constexpr std::array<Poly, 1> shapes() {
    Poly tail = linear(1, 4);
    tail.c[2] = 25.0 / 4.0;
    tail.c[3] = 4;
    return {power(linear(1, -0.5), 8) * tail};
  }
};

// One piece of the softened potential, in units h = 1 (see the header comment).
struct SofteningPiece {
  Real end = 0;        // the piece is [previous end, end)
  Real mass_const = 0;  // A_k
  Real pot_const = 0;   // B_k
  Poly force;           // sum_j a_j q^j              (phi~'(q) = A_k / q^2 + q * force(q))
  Poly potential;       // sum_j a_j / (j+2) q^j      (phi~(q) = -A_k / q + B_k + q^2 * potential(q))
  Poly dphi_dh;         // sum_j a_j (j+3)/(j+2) q^j  (phi~ + q phi~' = B_k + q^2 * dphi_dh(q))
};

template <class K>
struct SofteningTable {
  static constexpr int count = KernelPieces<K>::count;
  static constexpr Real support = K::support;

  static constexpr std::array<SofteningPiece, count> build() {
    const auto shape = KernelPieces<K>::shapes();
    const auto& b = KernelPieces<K>::breaks;
    const Real four_pi_sigma = 4 * kPi * K::norm(1);
    std::array<SofteningPiece, count> p{};
    Real mu = 0;  // enclosed mass at the start of the piece
    for (int k = 0; k < count; ++k) {
      p[k].end = b[k + 1];
      Real start_terms = 0, end_terms = 0;
      for (int j = 0; j + 3 < kMaxTerms; ++j) {
        const Real a = four_pi_sigma * shape[k].c[j] / (j + 3);
        p[k].force.c[j] = a;
        p[k].potential.c[j] = a / (j + 2);
        p[k].dphi_dh.c[j] = a * (j + 3) / (j + 2);
        start_terms += a * kernel_detail::ipow(b[k], j + 3);
        end_terms += a * kernel_detail::ipow(b[k + 1], j + 3);
      }
      p[k].mass_const = k == 0 ? 0 : mu - start_terms;
      mu = p[k].mass_const + end_terms;
    }
    Real outer = -1 / b[count];  // phi~ at the end of the piece being fixed
    for (int k = count - 1; k >= 0; --k) {
      const Real q = p[k].end;
      Real poly = 0;
      for (int j = kMaxTerms - 1; j >= 0; --j) poly = poly * q + p[k].potential.c[j];
      p[k].pot_const = outer + p[k].mass_const / q - q * q * poly;
      const Real q0 = b[k];
      Real poly0 = 0;
      for (int j = kMaxTerms - 1; j >= 0; --j) poly0 = poly0 * q0 + p[k].potential.c[j];
      outer = (k > 0 ? -p[k].mass_const / q0 : 0) + p[k].pot_const + q0 * q0 * poly0;
    }
    return p;
  }
  static constexpr std::array<SofteningPiece, count> pieces = build();
  // Number of coefficients to evaluate (the largest degree over pieces, plus one).
  static constexpr int terms() {
    int d = 0;
    for (const SofteningPiece& s : pieces) d = degree(s.force) > d ? degree(s.force) : d;
    return d + 1;
  }
  static constexpr int n_terms = terms();
};

}  // namespace sphark::softening_detail
