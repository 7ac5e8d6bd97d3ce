#include "sphark/boundaries/walls.hpp"

#include "sphark/boundaries/generic_map.hpp"

namespace sphark {

namespace {
template <class W>
MapResult generic_of(const W& wall, Real s, Real u, Real v) {
  return generic_map([&](Real t) { return wall.jacobian(t, u, v); }, s, wall.psi_max(u));
}
}  // namespace

MapResult generic_wall_map(const Wall<3>& wall, Real s, Real u, Real v) {
  return std::visit([&](const auto& w) { return generic_of(w, s, u, v); }, wall);
}
MapResult generic_wall_map(const Wall<2>& wall, Real s, Real u, Real v) {
  return std::visit([&](const auto& w) { return generic_of(w, s, u, v); }, wall);
}

}  // namespace sphark
