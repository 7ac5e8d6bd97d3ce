#pragma once
// Gravity of point masses (sink particles, Bate, Bonnell & Price 1995) on gas and on each other,
// with an optional softening length eps. Per unit G m of the point mass, at separation r:
//   None     phi = -1/r                         force_over_r = 1/r^3
//   Plummer  phi = -1/sqrt(r^2 + eps^2)         force_over_r = (r^2 + eps^2)^(-3/2)
//   Kernel   phi, force_over_r of kernel_softening.hpp with h = eps (Newtonian beyond
//            support * eps), the kernel K (Phantom softens sinks this way)
// so that a body at separation d = x - x_s (|d| = r) feels -G m_s force_over_r d and the point
// mass the reaction: each pair's forces are equal and opposite, momentum is conserved.
// Sink-gas: OpenMP over gas particles; each sink's reaction is summed over fixed blocks of gas
// (partial sums in block order), so nothing depends on the thread count. Sink-sink: direct.
// All functions ADD to their outputs (so they combine with self-gravity) and return the
// potential energy of the pairs they handled (each pair once).
#include <cstddef>
#include <vector>

#include "sphark/gravity/kernel_softening.hpp"
#include "sphark/gravity/self_gravity.hpp"
#include "sphark/kernels/kernels.hpp"

namespace sphark {

enum class PointMassSoftening { None, Plummer, Kernel };

struct SinkSoftening {
  PointMassSoftening kind = PointMassSoftening::None;
  Real length = 0;  // eps (Plummer) or the kernel's h (Kernel)
};

// Point masses, not owned: x is 3 x n column-major.
struct PointMasses {
  const Real* x = nullptr;
  const Real* m = nullptr;
  std::size_t n = 0;
};

// phi and force_over_r per unit G m at squared separation r2. Throws std::invalid_argument for
// a softened kind with length <= 0 (checked by the callers below, once per call).
template <class K = CubicSpline<3>>
inline PairGravity point_mass_pair(const SinkSoftening& s, Real r2) {
  if (s.kind == PointMassSoftening::Plummer) {
    const Real inv = 1 / std::sqrt(r2 + s.length * s.length);
    return {inv * inv * inv, -inv};
  }
  if (s.kind == PointMassSoftening::Kernel) return softened_pair<K>(r2, s.length, s.length);
  const Real inv_r = 1 / std::sqrt(r2);
  return {inv_r * inv_r * inv_r, -inv_r};
}

template <class K = CubicSpline<3>>
class SinkGasGravity {
 public:
  // Adds to gas_acc (3 x n_gas), gas_pot (n_gas), sink_acc (3 x n_sinks), sink_pot (n_sinks);
  // potentials may be null. Returns sum over (gas a, sink s) of G m_a m_s phi(r_as).
  Real add(Real G, const PointMasses& sinks, const GravitySources& gas, const SinkSoftening& softening, Real* gas_acc,
           Real* gas_pot, Real* sink_acc, Real* sink_pot);
  long allocations() const { return allocations_; }

 private:
  static constexpr std::size_t kBlock = 1024;  // gas particles per partial sum of the reactions
  std::vector<Real> partial_;                   // [block][sink][ax ay az pot energy]
  long allocations_ = 0;
};

// Every sink pair once, direct. Adds to sink_acc (3 x n) and sink_pot (n, may be null); returns
// the sink-sink potential energy.
template <class K = CubicSpline<3>>
Real add_sink_sink_gravity(Real G, const PointMasses& sinks, const SinkSoftening& softening, Real* sink_acc,
                           Real* sink_pot);

}  // namespace sphark
