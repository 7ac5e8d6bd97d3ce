#pragma once
// The gas state of the converging, rotating, magnetised test clump shared by the SPMHD tests
// (vector paths, multirate subsets): positions from a placement, v = -x plus a rotation and a
// wobble, and smooth u, B and psi that vary from particle to particle.
#include <cmath>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/initial/spheres.hpp"
#include "sphark/state/state_layout.hpp"

namespace sphark::test {

inline void fill_clump_gas(const ParticlePlacement& place, const StateLayout& layout, std::vector<Real>& y) {
  auto x = vector_field<3>(y.data(), layout, Field::Position);
  auto v = vector_field<3>(y.data(), layout, Field::Velocity);
  auto u = scalar_field(y.data(), layout, Field::InternalEnergy);
  auto B = vector_field<3>(y.data(), layout, Field::MagneticField);
  auto psi = scalar_field(y.data(), layout, Field::Psi);
  for (std::size_t a = 0; a < place.size(); ++a) {
    x.col(a) = Eigen::Map<const Vec<3>>(place.x.data() + 3 * a);
    v.col(a) = -x.col(a) + Vec<3>(-0.2 * x(1, a), 0.2 * x(0, a), 0.05 * std::sin(1.3 * a));
    u(a) = 1e-3 * (1 + 0.3 * std::sin(0.7 * a));
    B.col(a) = 1e-2 * Vec<3>(std::sin(3.0 * a), 0.5, -std::cos(1.0 * a));
    psi(a) = 1e-4 * std::cos(0.4 * a);
  }
}

}  // namespace sphark::test
