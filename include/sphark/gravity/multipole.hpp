#pragma once
// Cartesian multipole (source) and local (field) expansions of 1/r to quadrupole order for the
// mutual cell-cell interaction of the dual-tree walk (Dehnen 2000, ApJ 536, L39; 2002, JCP 179, 27).
// Derivation and the momentum argument: docs/gravity.md.
//
// A cell B (mass M, centre of mass z_B, second moment Q = sum_b m_b s_b s_b^T, s_b = x_b - z_B;
// its dipole vanishes) produces at x = z_A + s (R = z_A - z_B, g = 1/|.|, D^(n) = grad^n g(R))
//   psi(x) = M g(R + s) + (1/2) Q : grad^2 g(R + s),   Phi = -G psi,   acceleration = G grad psi.
// Truncated at total order 2 in (s, s_b) -- the terms that make the total force on A exactly
// minus the total force on B (see docs/gravity.md):
//   psi(z_A + s) ~ c0 + c1.s + (1/2) c2:ss + (1/6) c3:sss with
//   c0 = M D0 + (1/2) Q:D2,  c1 = M D1 + (1/2) Q:D3,  c2 = M D2,  c3 = M D3,
//   D0 = 1/r, D1 = -R/r^3, D2 = 3RR/r^5 - I/r^3, D3_ijk = -15 R_i R_j R_k / r^7
//                                                     + 3 (R_i d_jk + R_j d_ik + R_k d_ij) / r^5.
// c3 (from B's monopole) is what A's quadrupole contracts with: summed over A's particles,
// (1/2) sum_a m_a c3:s_a s_a = (1/2) M_B Q_A : D3, the partner of B's (1/2) M_A Q_B : D3.
// Symmetric tensors: sym2 = xx xy xz yy yz zz; sym3 = xxx xxy xxz xyy xyz xzz yyy yyz yzz zzz.
#include <cmath>

#include "sphark/core/types.hpp"

namespace sphark {

// T: Real, or a two-lane SIMD type (src/gravity/far_field_sums.hpp) for two sources at once.
template <class T>
struct LocalExpansionT {
  T c0{};
  T c1[3]{};
  T c2[6]{};
  T c3[10]{};
};
using LocalExpansion = LocalExpansionT<Real>;

// Adds the field of a source (mass, second moment quad in sym2) at separation R = z_A - z_B,
// given ir = 1 / |R|.
template <class T>
inline void add_far_field(LocalExpansionT<T>& L, const T R[3], T ir, T mass, const T quad[6]) {
  const T X = R[0], Y = R[1], Z = R[2];
  const T ir2 = ir * ir, ir3 = ir * ir2, ir5 = ir3 * ir2, ir7 = ir5 * ir2, ir9 = ir7 * ir2;
  // Q contractions: q = R.Q.R, t = tr Q, QR = Q R
  const T QRx = quad[0] * X + quad[1] * Y + quad[2] * Z;
  const T QRy = quad[1] * X + quad[3] * Y + quad[4] * Z;
  const T QRz = quad[2] * X + quad[4] * Y + quad[5] * Z;
  const T q = X * QRx + Y * QRy + Z * QRz, t = quad[0] + quad[3] + quad[5];
  L.c0 += mass * ir + 0.5 * (3.0 * q * ir5 - t * ir3);
  // (1/2) Q:D3 = (1/2) [-15 R q / r^7 + 3 (R t + 2 QR) / r^5]
  const T qr = -7.5 * q * ir7 + 1.5 * t * ir5, qq = 3.0 * ir5;
  const T m3 = mass * ir3;
  L.c1[0] += qr * X + qq * QRx - m3 * X;
  L.c1[1] += qr * Y + qq * QRy - m3 * Y;
  L.c1[2] += qr * Z + qq * QRz - m3 * Z;
  const T m5 = 3.0 * mass * ir5;
  // (1/2) Q:D4 = (1/2) [105 RR q / r^9 - 15 (I q + 2 (R QR + QR R) + RR t) / r^7 + 3 (I t + 2 Q) / r^5]
  const T a = 52.5 * q * ir9 - 7.5 * t * ir7 + m5, b = -15.0 * ir7, dg = -7.5 * q * ir7 + 1.5 * t * ir5 - m3, qf = qq;
  L.c2[0] += a * X * X + 2.0 * b * X * QRx + dg + qf * quad[0];
  L.c2[1] += a * X * Y + b * (X * QRy + Y * QRx) + qf * quad[1];
  L.c2[2] += a * X * Z + b * (X * QRz + Z * QRx) + qf * quad[2];
  L.c2[3] += a * Y * Y + 2.0 * b * Y * QRy + dg + qf * quad[3];
  L.c2[4] += a * Y * Z + b * (Y * QRz + Z * QRy) + qf * quad[4];
  L.c2[5] += a * Z * Z + 2.0 * b * Z * QRz + dg + qf * quad[5];
  const T m7 = -15.0 * mass * ir7;
  const T XX = X * X, YY = Y * Y, ZZ = Z * Z;
  L.c3[0] += m7 * XX * X + 3.0 * m5 * X;
  L.c3[1] += m7 * XX * Y + m5 * Y;
  L.c3[2] += m7 * XX * Z + m5 * Z;
  L.c3[3] += m7 * YY * X + m5 * X;
  L.c3[4] += m7 * X * Y * Z;
  L.c3[5] += m7 * ZZ * X + m5 * X;
  L.c3[6] += m7 * YY * Y + 3.0 * m5 * Y;
  L.c3[7] += m7 * YY * Z + m5 * Z;
  L.c3[8] += m7 * ZZ * Y + m5 * Y;
  L.c3[9] += m7 * ZZ * Z + 3.0 * m5 * Z;
}

inline void add_far_field(LocalExpansion& L, const Real R[3], Real mass, const Real quad[6]) {
  add_far_field<Real>(L, R, 1 / std::sqrt(R[0] * R[0] + R[1] * R[1] + R[2] * R[2]), mass, quad);
}

// v_ij = sum_k c3_ijk d_k (sym3 -> sym2)
inline void contract_sym3(const Real c3[10], const Real d[3], Real v[6]) {
  v[0] = c3[0] * d[0] + c3[1] * d[1] + c3[2] * d[2];
  v[1] = c3[1] * d[0] + c3[3] * d[1] + c3[4] * d[2];
  v[2] = c3[2] * d[0] + c3[4] * d[1] + c3[5] * d[2];
  v[3] = c3[3] * d[0] + c3[6] * d[1] + c3[7] * d[2];
  v[4] = c3[4] * d[0] + c3[7] * d[1] + c3[8] * d[2];
  v[5] = c3[5] * d[0] + c3[8] * d[1] + c3[9] * d[2];
}

// The same polynomial about z + d: (c0', c1') of psi(z + d + s') (exact for a cubic), for the
// value and gradient at a point d from the centre.
inline void value_and_gradient_at(const LocalExpansion& L, const Real d[3], Real& value, Real grad[3]) {
  Real v[6];
  contract_sym3(L.c3, d, v);
  const Real* c2 = L.c2;
  // gradient: c1 + (c2 + v/2) d;  value: c0 + c1.d + (1/2) d.(c2 + v/3) d
  const Real e[6] = {c2[0] + 0.5 * v[0], c2[1] + 0.5 * v[1], c2[2] + 0.5 * v[2],
                     c2[3] + 0.5 * v[3], c2[4] + 0.5 * v[4], c2[5] + 0.5 * v[5]};
  grad[0] = L.c1[0] + e[0] * d[0] + e[1] * d[1] + e[2] * d[2];
  grad[1] = L.c1[1] + e[1] * d[0] + e[3] * d[1] + e[4] * d[2];
  grad[2] = L.c1[2] + e[2] * d[0] + e[4] * d[1] + e[5] * d[2];
  const Real f[6] = {c2[0] + v[0] / 3, c2[1] + v[1] / 3, c2[2] + v[2] / 3,
                     c2[3] + v[3] / 3, c2[4] + v[4] / 3, c2[5] + v[5] / 3};
  const Real fd[3] = {f[0] * d[0] + f[1] * d[1] + f[2] * d[2], f[1] * d[0] + f[3] * d[1] + f[4] * d[2],
                      f[2] * d[0] + f[4] * d[1] + f[5] * d[2]};
  value = L.c0 + L.c1[0] * d[0] + L.c1[1] * d[1] + L.c1[2] * d[2] +
          0.5 * (fd[0] * d[0] + fd[1] * d[1] + fd[2] * d[2]);
}

// child += parent re-expanded about a point d from the parent's centre (every coefficient).
inline void add_shifted(LocalExpansion& child, const LocalExpansion& L, const Real d[3]) {
  Real v[6];
  contract_sym3(L.c3, d, v);
  Real value, grad[3];
  value_and_gradient_at(L, d, value, grad);
  child.c0 += value;
  for (int i = 0; i < 3; ++i) child.c1[i] += grad[i];
  for (int i = 0; i < 6; ++i) child.c2[i] += L.c2[i] + v[i];
  for (int i = 0; i < 10; ++i) child.c3[i] += L.c3[i];
}

}  // namespace sphark
