#include "sphark/boundaries/maps.hpp"

#include <algorithm>

namespace sphark {

std::string_view to_string(MapStatus status) {
  switch (status) {
    case MapStatus::Ok: return "ok";
    case MapStatus::BeyondAxis: return "ghost would cross the axis of symmetry";
    case MapStatus::NoRealSolution: return "no real solution (not enough volume on the ghost side)";
  }
  return "?";
}

Real depressed_cubic_root(Real k) {
  // z = (2/sqrt3) cos(acos(v)/3) for |v| <= 1, (2/sqrt3) cosh(acosh(v)/3) for v > 1,
  // v = (3 sqrt3 / 2) k (Viete). Largest real root of z^3 - z - k = 0.
  const Real sqrt3 = std::sqrt(3.0);
  const Real v = 1.5 * sqrt3 * k;
  if (v > 1) return 2 / sqrt3 * std::cosh(std::acosh(v) / 3);
  return 2 / sqrt3 * std::cos(std::acos(std::max(v, Real(-1))) / 3);
}

}  // namespace sphark
