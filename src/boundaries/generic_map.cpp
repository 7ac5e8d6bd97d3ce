#include "sphark/boundaries/generic_map.hpp"

#include <array>
#include <cmath>

namespace sphark {

namespace {
// 10-point Gauss-Legendre nodes and weights on [-1, 1] (positive half).
constexpr std::array<Real, 5> kNodes = {0.1488743389816312108848260, 0.4333953941292471907992659,
                                        0.6794095682990244062343274, 0.8650633666889845107320967,
                                        0.9739065285171717200779640};
constexpr std::array<Real, 5> kWeights = {0.2955242247147528701738930, 0.2692667193099963550912269,
                                          0.2190863625159820439955349, 0.1494513491505805931457763,
                                          0.0666713443086881375935688};

Real gauss10(const JacobianFn& J, Real a, Real b) {
  const Real m = 0.5 * (a + b), r = 0.5 * (b - a);
  Real sum = 0;
  for (int i = 0; i < 5; ++i) sum += kWeights[i] * (J(m - r * kNodes[i]) + J(m + r * kNodes[i]));
  return r * sum;
}

Real adaptive(const JacobianFn& J, Real a, Real b, Real whole, int depth) {
  const Real m = 0.5 * (a + b);
  const Real left = gauss10(J, a, m), right = gauss10(J, m, b);
  const Real halves = left + right;
  if (depth >= 30 || std::abs(halves - whole) <= 1e-14 * std::abs(halves) + 1e-300) return halves;
  return adaptive(J, a, m, left, depth + 1) + adaptive(J, m, b, right, depth + 1);
}
}  // namespace

Real integrate_jacobian(const JacobianFn& J, Real a, Real b) {
  if (a == b) return 0;
  return adaptive(J, a, b, gauss10(J, a, b), 0);
}

MapResult generic_map(const JacobianFn& J, Real s, Real psi_max, const GenericMapOptions& opt) {
  if (s == 0) return {0, MapStatus::Ok};
  const Real c = integrate_jacobian(J, s, 0);  // -G(s) > 0: the volume to be mirrored
  const auto F = [&](Real psi) { return integrate_jacobian(J, 0, psi) - c; };

  // Bracket [lo, hi] with F(lo) < 0 <= F(hi).
  Real lo = 0, hi = 0;
  if (std::isfinite(psi_max)) {
    if (F(psi_max) < 0) return {psi_max, MapStatus::NoRealSolution};
    hi = psi_max;
  } else {
    hi = std::max(-s, Real(1e-300));
    int doublings = 0;
    while (F(hi) < 0) {
      lo = hi;
      hi *= 2;
      if (++doublings > 2000) return {hi, MapStatus::NoRealSolution};
    }
  }

  Real psi = std::min(std::max(-s, lo), hi);  // the mirror as first guess
  for (int it = 0; it < opt.max_iterations; ++it) {
    const Real f = F(psi);
    if (f == 0) break;
    (f < 0 ? lo : hi) = psi;
    const Real j = J(psi);
    Real next = psi - f / j;
    if (!(j > 0) || !(next > lo && next < hi)) next = 0.5 * (lo + hi);  // bisection safeguard
    const Real step = std::abs(next - psi);
    psi = next;
    if (step <= opt.tolerance * std::max(Real(1), std::abs(psi)) || hi - lo <= 4e-16 * std::max(Real(1), hi)) break;
  }
  return {psi, MapStatus::Ok};
}

}  // namespace sphark
