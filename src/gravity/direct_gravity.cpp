// Direct summation (see sphark/gravity/direct_gravity.hpp).
#include "sphark/gravity/direct_gravity.hpp"

#include <algorithm>
#include <limits>

#include "sphark/gravity/kernel_softening.hpp"
#include "sphark/kernels/kernels.hpp"
#include "gravity_kernels.hpp"

namespace sphark {

template <class K>
void direct_field_at(const GravitySources& src, std::size_t a, Real G, Real* acceleration, Real* potential) {
  const Real* x = src.x;
  const Real* m = src.m;
  const Real* h = src.h;
  Real ax = 0, ay = 0, az = 0, pot = self_potential<K>(m[a], h[a]);
  for (std::size_t b = 0; b < src.n; ++b) {
    if (b == a) continue;
    const Real dx = x[3 * a] - x[3 * b], dy = x[3 * a + 1] - x[3 * b + 1], dz = x[3 * a + 2] - x[3 * b + 2];
    const PairGravity p = softened_pair<K>(dx * dx + dy * dy + dz * dz, h[a], h[b]);
    const Real c = m[b] * p.force_over_r;
    ax -= c * dx;
    ay -= c * dy;
    az -= c * dz;
    pot += m[b] * p.phi;
  }
  acceleration[0] = G * ax;
  acceleration[1] = G * ay;
  acceleration[2] = G * az;
  *potential = G * pot;
}

template <class K>
Real DirectGravity<K>::compute(const GravitySources& src, Real* acceleration, Real* potential) {
  const auto n = static_cast<std::ptrdiff_t>(src.n);
#pragma omp parallel for schedule(dynamic, 16)
  for (std::ptrdiff_t a = 0; a < n; ++a) {
    if (src.wanted && !src.wanted[a]) {
      std::fill_n(acceleration + 3 * a, 3, std::numeric_limits<Real>::quiet_NaN());
      potential[a] = std::numeric_limits<Real>::quiet_NaN();
      continue;
    }
    direct_field_at<K>(src, static_cast<std::size_t>(a), G_, acceleration + 3 * a, potential + a);
  }
  return src.wanted ? std::numeric_limits<Real>::quiet_NaN() : potential_energy(src.m, potential, src.n);
}

Real potential_energy(const Real* m, const Real* potential, std::size_t n) {
  Real e = 0;
  for (std::size_t a = 0; a < n; ++a) e += m[a] * potential[a];
  return 0.5 * e;
}

#define SPHARK_INSTANTIATE(K)   \
  template class DirectGravity<K>; \
  template void direct_field_at<K>(const GravitySources&, std::size_t, Real, Real*, Real*);
SPHARK_GRAVITY_KERNELS(SPHARK_INSTANTIATE)
#undef SPHARK_INSTANTIATE

}  // namespace sphark
