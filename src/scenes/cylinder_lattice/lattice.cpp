#include "sphark/scenes/cylinder_lattice/lattice.hpp"

#include <cmath>
#include <stdexcept>

namespace sphark {

Real lattice_spacing(const LatticeParams& p, std::size_t n) {
  const Real L = 2 * p.half_box;
  return std::sqrt((L * L - kPi * p.radius * p.radius) / static_cast<Real>(n));
}

PeriodicBox<2> lattice_box(const LatticeParams& p) {
  PeriodicBox<2> box;
  box.lo = Vec<2>::Constant(-p.half_box);
  box.hi = Vec<2>::Constant(p.half_box);
  box.periodic = {true, true};
  return box;
}

Wall<2> lattice_wall(const LatticeParams& p) { return Cylinder<2>{Vec<2>::Zero(), p.radius, FluidSide::Outside}; }

namespace {
const LatticeParams& checked(const LatticeParams& p) {
  if (!(p.radius > 0)) throw std::invalid_argument("LatticeSystem: the radius must be positive");
  if (!(p.radius < p.half_box)) throw std::invalid_argument("LatticeSystem: the obstacle must fit in the box");
  return p;
}
}  // namespace

LatticeSystem::LatticeSystem(std::size_t particles, const LatticeParams& params)
    : GhostWcsph<LatticeKernel>(particles, checked(params), lattice_wall(params), lattice_box(params)),
      lattice_(params) {}

}  // namespace sphark
