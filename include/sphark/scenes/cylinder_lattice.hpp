#pragma once
// Flow of a compressible liquid through a periodic lattice of cylinders (seed 004, §8): the
// 2D periodic box [-0.5, 0.5]^2 with a circular obstacle of radius R at the origin, ghost
// particles across its wall (seed 004, §2 approach C: equal masses, ghost at Psi(s) or Psi0(s)),
// a driving term dv_x/dt += (v0 - v_x)/tau (seed 004, eq. 36).
//
// SPH formulation (the paper's §2 and its silences are documented in docs/cylinder_lattice.md):
//   rho_a = sum_b m W(|x_a - x_b|, h_a),  h_a = eta (m / rho_a)^(1/2)  seed 004 eq. (1); seed 000 eq. (4)-(5)
//     summed over real AND ghost particles (equal masses, approach C). A ghost carries the
//     density, h, Omega and pressure of its inner particle and its velocity mirrored (seed 004
//     §1-2); its OWN support radius (eq. 1 solved at the ghost's position) is computed as well and
//     drives the accumulation event.
//   P = c_s^2 rho0 / 7 ((rho/rho0)^7 - 1) + P_b                         seed 000, eq. (26) (Tait) + background
//     P_b = background * c_s^2 rho0 / 7 > 0, so that P >= 0 (a ghost never pulls a real particle
//     towards and through the wall) for rho >= rho0 (1 - background)^(1/7): the default 0.15
//     covers rho >= 0.977 rho0 (docs/cylinder_lattice.md, "Background pressure"); 1 covers every rho.
//   dv_a/dt = - sum_b m [P_a/(Omega_a rho_a^2) grad W(h_a) + P_b/(Omega_b rho_b^2) grad W(h_b)]
//             + Monaghan viscosity (h_ab, grad W averaged) + (v0 - v_x)/tau x   (grad-h form of seed 000 eq. (27); seed 004 eq. (36))
//   dx_a/dt = v_a
// State: x, v of the real particles (density by summation). Ghosts are regenerated from the
// current positions inside every RHS evaluation.
//
// Events (root functions, integrate/ode_system.hpp):
//   g_0 = min_a (|x_a - c| - R)                    penetration: a particle crosses the wall
//   g_1 = min_ghost h_g / h_ref - accumulation      accumulation: a ghost's support collapses
#include <cstddef>
#include <string>
#include <vector>

#include "sphark/boundaries/ghosts.hpp"
#include "sphark/integrate/ode_system.hpp"
#include "sphark/neighbours/neighbour_search.hpp"
#include "sphark/state/state_layout.hpp"

namespace sphark {

struct LatticeParams {
  Real half_box = 0.5;    // box [-half_box, half_box]^2, periodic in x and y
  Real radius = 0.2;      // obstacle radius R (centre at the origin)
  Real rho0 = 1;          // reference density of the Tait EOS
  Real sound_speed = 5;   // c_s of the Tait EOS: 10 x the medium-resolution v0 = 0.5
  Real background = 0.15; // background pressure P_b in units of c_s^2 rho0 / 7 (1: P >= 0 for every rho)
  Real mass = 0;          // particle mass (all equal, real and ghost)
  Real eta = 1.3;         // h = eta (m/rho)^(1/2); Wendland C4 support H = 2h
  Real alpha = 0.1;       // Monaghan artificial viscosity
  Real v0 = 0.5;          // driving velocity, eq. (36)
  Real tau = 1;           // driving time, eq. (36); <= 0 switches the driving off
  GhostMap map = GhostMap::DensityPreserving;
  VelocityBc velocity = VelocityBc::FreeSlip;
  Real cfl = 0.25;        // dt <= cfl h_min / (c_max + |v|_max), dt <= cfl sqrt(h_min / a_max)
  Real h_ref = 0;         // uniform-lattice h (eta dx) for the accumulation event
  Real accumulation = 0.05;  // accumulation when a ghost's h < accumulation * h_ref ("H close to zero")
  Real h_tol = 1e-7;      // relative tolerance of the h-rho Newton solve
};

// P_b = background * c_s^2 rho0 / 7, added to the Tait pressure.
inline Real background_pressure(const LatticeParams& p) {
  return p.background * p.sound_speed * p.sound_speed * p.rho0 / 7;
}

// The uniform-lattice spacing of n particles in the fluid area (box minus disc).
Real lattice_spacing(const LatticeParams& p, std::size_t n);
// The box [-half_box, half_box]^2, periodic along x and y.
PeriodicBox<2> lattice_box(const LatticeParams& p);

class LatticeSystem final : public OdeSystem {
 public:
  LatticeSystem(std::size_t particles, LatticeParams params);

  const StateLayout& layout() const { return layout_; }
  const LatticeParams& params() const { return p_; }
  std::size_t particles() const { return n_; }

  std::size_t size() const override { return layout_.size(); }
  const StateLayout* state_layout() const override { return &layout_; }
  int rhs(Real t, const Real* y, Real* ydot) override;
  std::size_t position_offset() const override { return layout_.offset(Field::Position); }
  std::size_t velocity_offset() const override { return layout_.offset(Field::Velocity); }
  std::size_t position_size() const override { return layout_.field_size(Field::Position); }
  // CFL and force criteria at y (force: ydot's accelerations, or f(t, y) when ydot is null).
  Real max_stable_dt(Real t, const Real* y, const Real* ydot) override;
  int num_roots() const override { return 2; }
  int roots(Real t, const Real* y, Real* g) override;
  std::string last_error() const override { return error_; }

  // Ghosts, densities and h of state y (what rhs() does before the forces); 0 ok, else error.
  int prepare(const Real* y);
  // prepare(y) unless the positions of y are those of the last prepare (h, rho, ghost
  // positions depend on the positions alone).
  int prepare_if_moved(const Real* y);

  // After rhs()/prepare(): per particle (real first, then ghosts: their source's values) density,
  // h, pressure; min_ghost_h(): the smallest OWN support radius / 2 of a ghost.
  std::size_t ghost_count() const { return ghosts_.size(); }
  const std::vector<Real>& density() const { return rho_; }
  const std::vector<Real>& smoothing_length() const { return h_; }
  const std::vector<Real>& pressure() const { return pressure_; }
  const GhostLayer<2>& ghosts() const { return ghosts_; }
  const std::vector<Real>& all_positions() const { return xall_; }  // real then ghost, 2 each
  // sum over real-ghost pairs of m * (pair acceleration on the real particle) in the last rhs().
  Vec<2> wall_force() const { return wall_force_; }
  Real min_ghost_h() const;
  long rhs_calls() const { return rhs_calls_; }

 private:
  int solve_densities(std::size_t total);
  Real max_acceleration(Real t, const Real* y, const Real* ydot);

  LatticeParams p_;
  std::size_t n_;
  StateLayout layout_;
  PeriodicBox<2> box_;
  Wall<2> wall_;
  GhostLayer<2> ghosts_;
  NeighbourSearch<2> search_;
  std::vector<Real> xall_, vall_, mass_, rho_, h_, omega_, pressure_, q_;
  std::vector<Real> ghost_h_;     // each ghost's own h from eq. (1) at its position (accumulation)
  std::vector<Real> x_prepared_;  // positions of the last prepare()
  std::vector<Real> evaluated_y_, scratch_;  // the state of the last rhs(); its derivative buffer
  bool prepared_ = false;
  Real width_ = 0, max_accel_ = 0, h_min_ = 0;
  Vec<2> wall_force_ = Vec<2>::Zero();
  long rhs_calls_ = 0;
  std::string error_;
};

}  // namespace sphark
