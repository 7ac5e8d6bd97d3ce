// Point-mass (sink) gravity (see sphark/gravity/point_mass_gravity.hpp).
#include "sphark/gravity/point_mass_gravity.hpp"

#include <algorithm>
#include <stdexcept>

#include "reuse_buffer.hpp"
#include "gravity_kernels.hpp"

namespace sphark {

namespace {
void check(const SinkSoftening& s) {
  if (s.kind != PointMassSoftening::None && !(s.length > 0))
    throw std::invalid_argument("sink gravity: a softened point mass needs a softening length > 0");
}
}  // namespace

template <class K>
Real SinkGasGravity<K>::add(Real G, const PointMasses& sinks, const GravitySources& gas, const SinkSoftening& softening,
                            Real* gas_acc, Real* gas_pot, Real* sink_acc, Real* sink_pot) {
  check(softening);
  const std::size_t ns = sinks.n, blocks = (gas.n + kBlock - 1) / kBlock;
  if (gravity_detail::resize_reporting_growth(partial_, blocks * ns * 5)) ++allocations_;
  const auto nb = static_cast<std::ptrdiff_t>(blocks);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t blk = 0; blk < nb; ++blk) {
    Real* part = partial_.data() + static_cast<std::size_t>(blk) * ns * 5;
    std::fill(part, part + ns * 5, 0.0);
    const std::size_t a1 = std::min(gas.n, (static_cast<std::size_t>(blk) + 1) * kBlock);
    for (std::size_t a = static_cast<std::size_t>(blk) * kBlock; a < a1; ++a)
      for (std::size_t s = 0; s < ns; ++s) {
        const Real d[3] = {gas.x[3 * a] - sinks.x[3 * s], gas.x[3 * a + 1] - sinks.x[3 * s + 1],
                           gas.x[3 * a + 2] - sinks.x[3 * s + 2]};
        const PairGravity p = point_mass_pair<K>(softening, d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        const Real on_gas = G * sinks.m[s] * p.force_over_r, on_sink = G * gas.m[a] * p.force_over_r;
        for (int c = 0; c < 3; ++c) {
          gas_acc[3 * a + c] -= on_gas * d[c];
          part[5 * s + c] += on_sink * d[c];
        }
        if (gas_pot) gas_pot[a] += G * sinks.m[s] * p.phi;
        part[5 * s + 3] += G * gas.m[a] * p.phi;
        part[5 * s + 4] += G * gas.m[a] * sinks.m[s] * p.phi;
      }
  }
  Real energy = 0;
  for (std::size_t blk = 0; blk < blocks; ++blk)
    for (std::size_t s = 0; s < ns; ++s) {
      const Real* part = partial_.data() + (blk * ns + s) * 5;
      for (int c = 0; c < 3; ++c) sink_acc[3 * s + c] += part[c];
      if (sink_pot) sink_pot[s] += part[3];
      energy += part[4];
    }
  return energy;
}

template <class K>
Real add_sink_sink_gravity(Real G, const PointMasses& sinks, const SinkSoftening& softening, Real* sink_acc,
                           Real* sink_pot) {
  check(softening);
  Real energy = 0;
  for (std::size_t i = 0; i < sinks.n; ++i)
    for (std::size_t j = i + 1; j < sinks.n; ++j) {
      const Real d[3] = {sinks.x[3 * i] - sinks.x[3 * j], sinks.x[3 * i + 1] - sinks.x[3 * j + 1],
                         sinks.x[3 * i + 2] - sinks.x[3 * j + 2]};
      const PairGravity p = point_mass_pair<K>(softening, d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      for (int c = 0; c < 3; ++c) {
        sink_acc[3 * i + c] -= G * sinks.m[j] * p.force_over_r * d[c];
        sink_acc[3 * j + c] += G * sinks.m[i] * p.force_over_r * d[c];
      }
      if (sink_pot) sink_pot[i] += G * sinks.m[j] * p.phi, sink_pot[j] += G * sinks.m[i] * p.phi;
      energy += G * sinks.m[i] * sinks.m[j] * p.phi;
    }
  return energy;
}

#define SPHARK_INSTANTIATE(K) \
  template class SinkGasGravity<K>; \
  template Real add_sink_sink_gravity<K>(Real, const PointMasses&, const SinkSoftening&, Real*, Real*);
SPHARK_GRAVITY_KERNELS(SPHARK_INSTANTIATE)
#undef SPHARK_INSTANTIATE

}  // namespace sphark
