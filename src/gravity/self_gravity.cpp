// Solver choice, factory and time-step helpers (see sphark/gravity/self_gravity.hpp).
#include "sphark/gravity/self_gravity.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "sphark/gravity/direct_gravity.hpp"
#include "sphark/gravity/tree_gravity.hpp"
#include "sphark/kernels/kernels.hpp"
#include "gravity_kernels.hpp"

namespace sphark {

GravitySolver parse_gravity_solver(std::string_view name) {
  if (name == "direct") return GravitySolver::Direct;
  if (name == "tree") return GravitySolver::Tree;
  throw std::invalid_argument("unknown gravity solver '" + std::string(name) + "' (choose tree or direct)");
}

std::string_view gravity_solver_name(GravitySolver s) { return s == GravitySolver::Direct ? "direct" : "tree"; }

GravityOpening parse_gravity_opening(std::string_view name) {
  if (name == "fixed") return GravityOpening::Fixed;
  if (name == "mass") return GravityOpening::Mass;
  throw std::invalid_argument("unknown tree opening '" + std::string(name) + "' (choose fixed or mass)");
}

std::string_view gravity_opening_name(GravityOpening o) { return o == GravityOpening::Fixed ? "fixed" : "mass"; }

template <class K>
std::unique_ptr<SelfGravity> make_self_gravity(GravitySolver solver, const GravityOptions& options) {
  if (solver == GravitySolver::Direct) return std::make_unique<DirectGravity<K>>(options);
  return std::make_unique<TreeGravity<K>>(options);
}

#define SPHARK_INSTANTIATE(K) template std::unique_ptr<SelfGravity> make_self_gravity<K>(GravitySolver, const GravityOptions&);
SPHARK_GRAVITY_KERNELS(SPHARK_INSTANTIATE)
#undef SPHARK_INSTANTIATE

void acceleration_magnitudes(const Real* a, std::size_t n, Real* magnitude) {
  for (std::size_t i = 0; i < n; ++i)
    magnitude[i] = std::sqrt(a[3 * i] * a[3 * i] + a[3 * i + 1] * a[3 * i + 1] + a[3 * i + 2] * a[3 * i + 2]);
}

Real gravity_time_step(const Real* h, const Real* a, std::size_t n) {
  Real dt = std::numeric_limits<Real>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    const Real a2 = a[3 * i] * a[3 * i] + a[3 * i + 1] * a[3 * i + 1] + a[3 * i + 2] * a[3 * i + 2];
    if (a2 > 0) dt = std::min(dt, std::sqrt(h[i] / std::sqrt(a2)));
  }
  return dt;
}

}  // namespace sphark
