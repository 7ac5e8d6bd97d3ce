#pragma once
// Weakly compressible SPH with variable h ("grad-h") and ghost particles across a curved wall
// (seed 004, §2 approach C: equal masses, the ghost of a particle at distance s from the wall
// placed at Psi(s) or Psi0(s)), in a box that may be periodic; the kernel is a template
// parameter like the other schemes' (kernels/kernels.hpp). 2D.
//
//   rho_a = sum_b m W(|x_a - x_b|, h_a),  h_a = eta (m / rho_a)^(1/2)  seed 004 eq. (1); seed 000 eqs. (4)-(5)
//     summed over real AND ghost particles (equal masses, approach C). A ghost carries the
//     density, h, Omega and pressure of its inner particle and its velocity mirrored (seed 004
//     §1-2); its OWN support radius (eq. 1 solved at the ghost's position) is computed as well and
//     drives the accumulation event.
//   P = c_s^2 rho0 / 7 ((rho/rho0)^7 - 1) + P_b                         seed 000, eq. (26) (Tait) + background
//     P_b = background * c_s^2 rho0 / 7 >= 0 (docs/cylinder_lattice.md, "Background pressure").
//   dv_a/dt = - sum_b m [P_a/(Omega_a rho_a^2) grad W(h_a) + P_b/(Omega_b rho_b^2) grad W(h_b)]
//             + Monaghan viscosity (h_ab, grad W averaged) + (v0 - v_x)/tau x   (grad-h form of seed 000 eq. (27); seed 004 eq. (36))
//   dx_a/dt = v_a
// State: x, v of the real particles (density by summation). Ghosts are regenerated from the
// current positions inside every RHS evaluation.
//
// Events (root functions, integrate/ode_system.hpp):
//   g_0 = min_a (-s_a)                             penetration: a particle crosses the wall
//   g_1 = min_ghost h_g / h_ref - accumulation      accumulation: a ghost's support collapses
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sphark/boundaries/ghosts.hpp"
#include "sphark/integrate/ode_system.hpp"
#include "sphark/neighbours/neighbour_search.hpp"
#include "sphark/parallel/communicator.hpp"
#include "sphark/state/state_layout.hpp"

namespace sphark {

struct GhostWcsphParams {
  Real rho0 = 1;          // reference density of the Tait EOS
  Real sound_speed = 5;   // c_s of the Tait EOS
  Real background = 0.15; // background pressure P_b in units of c_s^2 rho0 / 7
  Real mass = 0;          // particle mass (all equal, real and ghost)
  Real eta = 1.3;         // h = eta (m/rho)^(1/2)
  Real alpha = 0.1;       // Monaghan artificial viscosity
  Real v0 = 0.5;          // driving velocity, seed 004 eq. (36)
  Real tau = 1;           // driving time, eq. (36); <= 0 switches the driving off
  GhostMap map = GhostMap::DensityPreserving;
  VelocityBc velocity = VelocityBc::FreeSlip;
  Real cfl = 0.25;        // dt <= cfl h_min / (c_max + |v|_max), dt <= cfl sqrt(h_min / a_max)
  Real h_ref = 0;         // uniform-lattice h (eta dx) for the accumulation event (0: no event)
  Real accumulation = 0.05;  // accumulation when a ghost's h < accumulation * h_ref ("H close to zero")
  Real h_tol = 1e-7;      // relative tolerance of the h-rho Newton solve
};

// P_b = background * c_s^2 rho0 / 7, added to the Tait pressure.
inline Real background_pressure(const GhostWcsphParams& p) {
  return p.background * p.sound_speed * p.sound_speed * p.rho0 / 7;
}

namespace ghost_detail {
struct Halo;  // src/schemes/ghost_wcsph/ghost_wcsph_distributed.cpp
}

template <class K>
class GhostWcsph : public OdeSystem {
 public:
  // `box` bounds the particles (periodic along its periodic axes); the fluid lies on the
  // s < 0 side of `wall`. Throws std::invalid_argument for bad parameters.
  GhostWcsph(std::size_t particles, GhostWcsphParams params, Wall<2> wall, PeriodicBox<2> box);
  ~GhostWcsph() override;

  // Distributed runs (src/schemes/ghost_wcsph/ghost_wcsph_distributed.cpp; docs/scaling.md,
  // "The lattice"): this rank holds the particles `ids` of the scheme built with every particle
  // (particle k = global id k). Every evaluation is then collective: a halo of the other ranks'
  // particles within reach (the list radius plus twice the ghost layer: their ghosts too, which
  // every rank places itself from their positions), the density solve of this rank's particles
  // and ghosts with every decision (list radius, retries, the layer's width) taken from the
  // maxima over all ranks, then h, rho and Omega of the halo from their owners. Rows are summed
  // in the serial order (keys: a particle's global id; a ghost's, N + its source's), so a
  // distributed run equals the serial one bit for bit.
  void distribute(Communicator comm, const std::vector<std::int64_t>& ids);
  // Collective, between steps (a migration): this rank now holds `ids`; restore_migrated() with
  // their migration_data() then, so that the run goes on as the serial one.
  void set_particles(std::vector<std::int64_t> ids);
  bool distributed() const { return halo_ != nullptr; }
  const std::vector<std::int64_t>& ids() const;
  const Communicator& communicator() const;
  // Per particle (particle-major): h, rho, Omega, the own h of its ghost (NaN: none) and the
  // positions they were solved at; then whether they are solved.
  static constexpr int kMigrationValues = 6;
  std::vector<Real> migration_data() const;
  void restore_migrated(std::span<const Real> data);

  const StateLayout& layout() const { return layout_; }
  const GhostWcsphParams& scheme_params() const { return p_; }
  std::size_t particles() const { return n_; }

  std::size_t size() const override { return layout_.size(); }
  const StateLayout* state_layout() const override { return &layout_; }
  int rhs(Real t, const Real* y, Real* ydot) override;
  std::size_t position_offset() const override { return layout_.offset(Field::Position); }
  std::size_t velocity_offset() const override { return layout_.offset(Field::Velocity); }
  std::size_t position_size() const override { return layout_.field_size(Field::Position); }
  // CFL and force criteria at y (force: ydot's accelerations, or f(t, y) when ydot is null).
  Real max_stable_dt(Real t, const Real* y, const Real* ydot) override;
  // Each particle's own step (serial only): max_stable_dt's criteria with its own h, sound speed,
  // speed and acceleration (ydot's, or from an evaluation at y); no subset evaluation
  // (supports_subsets() stays false): the lattice reports its step levels (issue #17).
  int particle_stable_dt(Real t, const Real* y, const Real* ydot, Real* dt) override;
  int num_roots() const override { return 2; }
  int roots(Real t, const Real* y, Real* g) override;
  std::string last_error() const override { return error_; }
  // Restart (ode_system.hpp): each h-rho solve starts Newton from the previous h of the real
  // particles, so the converged h depends on that start at round-off; resume_data() is that h,
  // resume(h) hands it back (positive, finite, one per particle) and the next solve takes each as
  // the root where it is one. (The ghosts' own h, the accumulation diagnostic, start from their
  // source's h and are solved again.)
  std::vector<Real> resume_data() const override { return {h_.begin(), h_.begin() + static_cast<std::ptrdiff_t>(n_)}; }
  void resume(std::span<const Real> h) override;
  ResumeShape resume_shape() const override { return {1, 0}; }  // h per particle

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
  void pair_forces(Real* ydot);  // rhs() after prepare(): the forces of the prepared state
  Real stable_step(Real h, Real c, Real speed, Real accel) const;  // max_stable_dt's criteria
  int solve_densities(std::size_t total);
  void pressures(std::size_t total);  // P and P / (Omega rho^2) of every slot
  // Distributed (ghost_wcsph_distributed.cpp): the collective prepare, its solve with the halo,
  // the halo and lists for the solved h (after a migration), and what both finish with.
  int distributed_prepare(const Real* y, bool solve);
  int distributed_solve(const Real* x, const Real* v, Real width, std::string& message);
  void link_halo(const Real* x, const Real* v, Real width, Real r_build);
  void finish_distributed_prepare(const Real* x);
  bool is_ghost(std::size_t i) const { return i >= n_ && (i < n_ + ghosts_.size() || i >= halo_ghost_begin_); }
  int prepare_if_moved_distributed(const Real* y);
  std::unique_ptr<ghost_detail::Halo> halo_;
  std::size_t halo_ghost_begin_ = static_cast<std::size_t>(-1);  // distributed: first halo ghost (serial: none)
  bool relink_ = false;  // distributed: solved values restored after a migration, halo and lists not built
  Real r_build_ = 0;     // distributed: the list radius of the last solve
  Real width_used_ = 0;  // distributed: the ghost layer's width of the last solve
  int place_ghosts_and_densities(const Real* x, const Real* v);
  Real max_acceleration(Real t, const Real* y, const Real* ydot);

  GhostWcsphParams p_;
  std::size_t n_;
  StateLayout layout_;
  PeriodicBox<2> box_;
  Wall<2> wall_;
  Real mirror_limit_;  // the mirror map's range |s| <= limit (a cylinder's radius; a plane: none)
  GhostLayer<2> ghosts_;
  NeighbourSearch<2> search_;
  std::vector<Real> xall_, vall_, mass_, rho_, h_, omega_, pressure_, q_;
  std::vector<Real> ghost_h_;     // each ghost's own h from eq. (1) at its position (accumulation)
  std::vector<Real> x_prepared_;  // positions of the last prepare()
  std::vector<Real> evaluated_y_, scratch_;  // the state of the last rhs(); its derivative buffer
  bool prepared_ = false;
  bool h_given_ = false;  // set by resume(): the next solve takes the real particles' h as roots
  Real width_ = 0, max_accel_ = 0, h_min_ = 0;
  Vec<2> wall_force_ = Vec<2>::Zero();
  long rhs_calls_ = 0;
  std::string error_;
};

}  // namespace sphark
