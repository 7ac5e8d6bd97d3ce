#include "sphark/diagnostics/wcsph_diagnostics.hpp"

#include <algorithm>
#include <cmath>

#include "sphark/kernels/kernel_list.hpp"
#include "sphark/operators/tait_eos.hpp"

namespace sphark {

template <int D, class Kernel>
WcsphDiagnostics<D> wcsph_diagnostics(WcsphSystem<D, Kernel>& system, Real t, const Real* y) {
  const std::vector<Real>& div_v = system.div_v(t, y);
  const WcsphParams<D>& p = system.params();
  const StateLayout& L = system.layout();
  WcsphDiagnostics<D> d;
  const auto x = vector_field<D>(y, L, Field::Position);
  const auto v = vector_field<D>(y, L, Field::Velocity);
  const auto rho = scalar_field(y, L, Field::Density);
  const Real* psi = p.cleaning ? y + L.offset(Field::Psi) : nullptr;
  const Real m = p.mass, r0 = p.rho0, ch = p.cleaning_speed();
  const std::size_t n = L.particles();
  for (std::size_t a = 0; a < n; ++a) {
    d.kinetic_energy += 0.5 * m * v.col(a).squaredNorm();
    d.momentum += m * v.col(a);
    const Real r = rho[a];
    d.internal_energy += m * tait_specific_energy(r, r0, p.sound_speed);  // of the Tait EOS (26)
    if (p.body_potential) d.potential_energy += m * p.body_potential(Vec<D>(x.col(a)));
    if (psi) d.psi_energy += m * psi[a] * psi[a] / (2 * ch * ch * r * r);  // eq. (37)
    d.mean_abs_div_v += std::abs(div_v[a]);
    d.max_rel_density_error = std::max(d.max_rel_density_error, std::abs(r - r0) / r0);
  }
  d.mean_abs_div_v /= static_cast<Real>(n);
  d.total_energy = d.kinetic_energy + d.internal_energy + d.potential_energy + d.psi_energy;
  return d;
}

template <int D, class Kernel>
ParticleFrame WcsphFrame::build(WcsphSystem<D, Kernel>& system, Real t, const Real* y) {
  const StateLayout& L = system.layout();
  const std::size_t n = L.particles();
  const Real* v = y + L.offset(Field::Velocity);
  velocity_.assign(v, v + D * n);
  const Real* rho = y + L.offset(Field::Density);
  density_.assign(rho, rho + n);
  pressure_ = system.pressure(t, y);
  div_v_ = system.div_v(t, y);
  ParticleFrame f;
  f.dim = D;
  f.count = n;
  f.positions = y + L.offset(Field::Position);
  f.arrays = {{"velocity", velocity_.data(), D},
              {"density", density_.data(), 1},
              {"pressure", pressure_.data(), 1},
              {"div_v", div_v_.data(), 1}};
  if (L.has(Field::Psi)) {
    const Real* psi = y + L.offset(Field::Psi);
    psi_.assign(psi, psi + n);
    f.arrays.push_back({"psi", psi_.data(), 1});
  }
  return f;
}

#define SPHARK_WCSPH_DIAGNOSTICS_D(D, K)                                                   \
  template WcsphDiagnostics<D> wcsph_diagnostics(WcsphSystem<D, K<D>>&, Real, const Real*); \
  template ParticleFrame WcsphFrame::build(WcsphSystem<D, K<D>>&, Real, const Real*);
#define SPHARK_WCSPH_DIAGNOSTICS(K) SPHARK_WCSPH_DIAGNOSTICS_D(2, K) SPHARK_WCSPH_DIAGNOSTICS_D(3, K)
SPHARK_KERNELS(SPHARK_WCSPH_DIAGNOSTICS)
#undef SPHARK_WCSPH_DIAGNOSTICS_D
#undef SPHARK_WCSPH_DIAGNOSTICS

}  // namespace sphark
