#pragma once
// Self-gravity of SPH particles with kernel softening (softening length = each particle's h;
// Price & Monaghan 2007), isolated boundaries, 3D. Two solvers behind one interface:
//   GravitySolver::Direct  O(N^2) direct summation, the reference (direct_gravity.hpp)
//   GravitySolver::Tree    O(N log N) symmetric dual-tree walk with quadrupoles (tree_gravity.hpp)
// Both are OpenMP-parallel, conserve linear momentum to round-off, give results that do not
// depend on the thread count (bit for bit), and allocate nothing after the first call with the
// same particle count. The potential includes each particle's self term G m_a phi(0, h_a), so
// that E = (1/2) sum_a m_a Phi_a is the energy whose gradient (with the grad-h term,
// gravity_grad_h.hpp) is the force. Positions are used as given (no periodic images: periodic
// hydrodynamics with isolated gravity, no Ewald sum, as Phantom; see docs/gravity.md).
#include <cstddef>
#include <memory>
#include <string_view>

#include <cstdint>

#include "sphark/core/types.hpp"

namespace sphark {

// Particle data, not owned. x: 3 x n column-major (x0 y0 z0 x1 ...), as vector_field<3> gives.
struct GravitySources {
  const Real* x = nullptr;
  const Real* m = nullptr;
  const Real* h = nullptr;  // softening lengths (the SPH h); h = 0: unsoftened, no self term
  std::size_t n = 0;
  // Per particle, 1 = its field is wanted (the active particles of a multirate evaluation);
  // nullptr: all. Every particle is still a source; the unwanted ones' acceleration and potential
  // are set to NaN (not computed), and compute() returns a NaN potential energy.
  const std::uint8_t* wanted = nullptr;
};

enum class GravitySolver { Direct, Tree };

// "direct" | "tree"; throws std::invalid_argument naming the choices otherwise.
GravitySolver parse_gravity_solver(std::string_view name);
std::string_view gravity_solver_name(GravitySolver s);

// How the tree's opening angle varies between cells (dual_tree_walk.hpp):
//   Fixed  every cell opens at theta: A, B interact by multipoles iff r_A + r_B < theta |z_A - z_B|
//   Mass   Dehnen (2002, JCP 179, 27; falcON): cell C opens at theta(M_C), with
//          theta^5 / (1 - theta)^2 = theta_0^5 / (1 - theta_0)^2 (M_root / M_C)^(1/3),
//          theta_0 = theta the root's; A, B interact iff r_A / theta_A + r_B / theta_B < |z_A - z_B|
enum class GravityOpening { Fixed, Mass };

// "fixed" | "mass"; throws std::invalid_argument naming the choices otherwise.
GravityOpening parse_gravity_opening(std::string_view name);
std::string_view gravity_opening_name(GravityOpening o);

// The default angle of each criterion; the two give the same force errors against direct
// summation (median and 99th percentile, docs/gravity.md "Mass-dependent opening").
inline constexpr Real kDefaultFixedTheta = 0.5;
inline constexpr Real kDefaultMassTheta0 = 0.35;
constexpr Real default_theta(GravityOpening o) { return o == GravityOpening::Fixed ? kDefaultFixedTheta : kDefaultMassTheta0; }

struct GravityOptions {
  Real G = 1;          // gravitational constant in code units
  Real theta = kDefaultFixedTheta;  // tree: the opening angle (Fixed), or the root's (Mass)
  int leaf_size = 8;   // tree: particles per leaf at most
  GravityOpening opening = GravityOpening::Fixed;
};

class SelfGravity {
 public:
  virtual ~SelfGravity() = default;
  // Accelerations (3 x n, overwritten) and potentials per unit mass (n, overwritten, self term
  // included) of the particles; returns the potential energy (1/2) sum_a m_a Phi_a.
  virtual Real compute(const GravitySources& src, Real* acceleration, Real* potential) = 0;
  virtual GravitySolver solver() const = 0;
  // Calls so far that had to enlarge a buffer (all others allocated nothing).
  virtual long allocations() const = 0;
};

// K: a 3D kernel of kernels.hpp (CubicSpline<3>, QuinticSpline<3>, WendlandC2<3>, WendlandC4<3>,
// WendlandC6<3>). Throws std::invalid_argument for theta outside (0, 1) or leaf_size < 1.
template <class K>
std::unique_ptr<SelfGravity> make_self_gravity(GravitySolver solver, const GravityOptions& options = {});

// |a| per particle (acc: 3 x n) into magnitude (n).
void acceleration_magnitudes(const Real* acceleration, std::size_t n, Real* magnitude);
// min_a sqrt(h_a / |a_a|): the gravity time-step scale (a scheme multiplies it by its safety
// factor in max_stable_dt). +infinity when every |a| = 0 or n = 0.
Real gravity_time_step(const Real* h, const Real* acceleration, std::size_t n);

}  // namespace sphark
