#pragma once
// Smoothed particle magnetohydrodynamics with constrained hyperbolic/parabolic divergence
// cleaning (seed 000, §II; Tricco & Price 2012). An OdeSystem: the state holds only what the
// variant needs (StateLayout):
//   evolve_particles:  x (D), v (D), u (1, not with a barotropic EOS), then B (3) or Euler alpha (1),
//                      then psi (1) if cleaning
//   cleaning subsystem (fixed particles, §IV-A):  B (3), psi (1)
// Density, h and Omega come from summation each RHS (seed 000, eqs. (4)-(5)). The psi damping
// -psi/tau is the stiff diagonal c = sigma c_h / h_a on the psi entries.
//
// The RHS is gather-form (each particle sums its own neighbours; OpenMP over particles, no
// races, results independent of the thread count), and allocates nothing after the first call
// unless a rebuilt Verlet list outgrows its buffers. Per-particle quantities of the pair loops are
// kept as structure-of-arrays, filled once per RHS (prepare()).
//
// Memory order: internally particles live in "slots" sorted by neighbour-grid cell, renewed at
// every list rebuild, so that the pair loops read neighbours that are close in memory (a
// scrambled order costs 2-6x). perm_[slot] is the particle (state index); inputs are gathered
// from the state and derivatives scattered back. Neighbour rows are sorted by particle index,
// so every sum runs in the same order whatever the slots: results do not depend on them.
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sphark/integrate/ode_system.hpp"
#include "sphark/kernels/kernels.hpp"
#include "sphark/neighbours/neighbour_method.hpp"
#include "sphark/parallel/communicator.hpp"
#include "sphark/schemes/spmhd/spmhd_options.hpp"
#include "sphark/state/state_layout.hpp"

namespace sphark {

namespace spmhd_detail {
template <int D>
class Halo;  // src/schemes/spmhd/spmhd_halo.hpp
}

template <int D, class K = CubicSpline<D>>
class SpmhdScheme final : public OdeSystem {
 public:
  // masses: one per particle. fixed_positions (D x N, column-major) are required when
  // !opt.evolve_particles and ignored otherwise. Throws std::invalid_argument on bad input.
  SpmhdScheme(std::vector<Real> masses, SpmhdOptions opt, std::optional<PeriodicBox<D>> box = std::nullopt,
              std::vector<Real> fixed_positions = {});
  ~SpmhdScheme() override;
  SpmhdScheme(SpmhdScheme&&) noexcept;

  // Distributed runs (src/schemes/spmhd/spmhd_distributed.cpp; docs/scaling.md, "SPMHD"): the
  // scheme holds the particles `ids` (global ids < 2^32) of this rank, the scheme having been
  // built with every particle, particle k being global id k (their masses are kept). Every
  // call that evaluates (rhs, max_stable_dt, stiff_diagonal, evaluate) is then collective: it
  // exchanges a halo of the other ranks' particles within reach (the state, then h, rho and
  // Omega after the density solve), and every rank takes the same decisions (list rebuilds, the
  // density solve's retries, failures). Rows are summed in global-id order, so a distributed
  // run reproduces the serial one bit for bit. For moving particles with the magnetic field,
  // or fixed particles (the cleaning subsystem), without gravity or sinks; the stepper sees the
  // local state (StepperOptions::communicator).
  void distribute(Communicator comm, const std::vector<std::int64_t>& ids);
  // Collective, between steps (a migration): this rank now holds `ids` with `masses`; then
  // restore_migrated() with their migration_data(), or resume() (a restart: the next evaluation
  // solves from the starts).
  void set_particles(std::vector<std::int64_t> ids, std::vector<Real> masses);
  // What a particle's density solve has reached, so that a migrated particle continues exactly as
  // in the serial run (spmhd_migration.hpp): per particle (particle-major) the last iterate, h,
  // rho, Omega, div v and the positions they were solved at; then the time of h and whether div v
  // is known. The next evaluation at those positions then solves nothing, as the serial run's
  // (which skips the solve when the positions are unchanged).
  static constexpr int kMigrationValues = 5 + D;
  std::vector<Real> migration_data() const;
  void restore_migrated(std::span<const Real> data);
  bool distributed() const { return halo_ != nullptr; }
  const std::vector<std::int64_t>& ids() const;  // distributed: this rank's global ids
  const Communicator& communicator() const;      // distributed: the ranks'; else a serial one

  const StateLayout& layout() const { return layout_; }
  const SpmhdOptions& options() const { return opt_; }
  std::size_t particles() const { return n_; }
  const std::vector<Real>& masses() const { return m_; }

  std::size_t size() const override { return layout_.size(); }
  const StateLayout* state_layout() const override { return &layout_; }
  int rhs(Real t, const Real* y, Real* ydot) override;
  bool has_stiff_diagonal() const override { return opt_.cleaning != Cleaning::None && opt_.sigma > 0; }
  int stiff_diagonal(Real t, const Real* y, Real* c) override;
  std::size_t position_offset() const override;
  std::size_t velocity_offset() const override;
  std::size_t position_size() const override { return opt_.evolve_particles ? D * n_ : 0; }
  // Courant limit min_a C h_a / v_sig,a, v_sig,a = max(c_h,a, c_f,a) + (1 + beta_visc)|v_a|, a
  // function of y alone: h, rho, the fast speeds c_f and c_h are derived from y as in rhs() (the
  // density solve is memoised on the exact positions; the Newton start, the previous h, moves the
  // result at round-off only). +inf when no particle has a signal speed. On failure (a non-finite
  // wave speed, an h solve that does not converge) a quiet NaN, with last_error() saying why:
  // callers must treat NaN as "no step possible" (every comparison with it is false).
  Real max_stable_dt(Real t, const Real* y, const Real* ydot) noexcept override;
  // Each gas particle's own stable step at y (particle order; what max_stable_dt() minimises):
  // courant[a] = C h_a / v_sig,a and, with gravity, force[a] = force_courant sqrt(h_a / |dv_a/dt|)
  // (accelerations from ydot, or f(t, y) when null); +inf where a criterion does not apply (no
  // signal speed, no acceleration, no gravity). 0, or 1 with last_error() saying why.
  int stable_steps(Real t, const Real* y, const Real* ydot, std::vector<Real>& courant, std::vector<Real>& force) noexcept;
  std::string last_error() const override { return error_; }

  // Multirate (issue #17; src/schemes/spmhd/spmhd_subsets.cpp), for moving particles: the
  // derivatives of the particles `active` only (gas, then sinks: the layout's particle order),
  // each against all its neighbours. The pair loops (hydrodynamics, MHD, cleaning, gravity's
  // grad-h term) run over the active gas only; density and h (summation, memoised on the
  // positions), the gravity tree and the sink forces are computed for all and kept for the
  // active particles. particle_stable_dt: min(Courant, force criterion) of each gas particle
  // (stable_steps), capped at 4 x that of any neighbour within the kernel support (Saitoh &
  // Makino 2009); a sink's is the shortest gas step. active_stable_dt: that of each active gas
  // particle; of every other gas particle 4 x the least own step of its active neighbours (the
  // limiter's wake-up, as Phantom's), and its own step where its density was solved at (t, y) (the
  // active ones' neighbourhoods); of a sink the shortest active gas step. Its work: the rows
  // of the active particles, and O(N) per-particle arithmetic.
  bool supports_subsets() const override { return opt_.evolve_particles && !halo_; }
  int rhs_subset(Real t, const Real* y, std::span<const std::size_t> active, Real* ydot) override;
  int particle_stable_dt(Real t, const Real* y, const Real* ydot, Real* dt) override;
  int active_stable_dt(Real t, const Real* y, const Real* ydot, std::span<const std::size_t> active,
                       Real* dt) override;

  // Number of RHS evaluations so far.
  long rhs_evaluations() const { return rhs_calls_; }
  // Number of neighbour-list builds so far (Verlet reuse: far fewer than RHS evaluations).
  long neighbour_builds() const { return builds_; }
  // Makes the next RHS build its neighbour lists afresh (tests, benchmarks of the rebuild).
  void drop_neighbour_lists() { built_ = false; }
  // The current neighbour lists (pairs within the list radii at the last build: radii_).
  // Its particle numbers are the scheme's internal slots (see below), not state indices.
  const AdaptiveNeighbourSearch<D>& neighbours() const { return ns_; }
  // Pairs a-b (ordered, a != b) with |x_a - x_b| < K::support * max(h_a, h_b) at the last RHS:
  // the pair interactions the force loop evaluated.
  std::size_t interacting_pairs() const { return interacting_pairs_; }
  // Newton (or bisection) steps of the h solve so far, summed over particles.
  double h_iterations_total() const { return h_iterations_; }
  // Density / h solves so far, one per particle solved (not counting attempts retried with longer
  // lists; subset evaluations solve fewer than N).
  long density_solves() const { return density_solves_; }
  long gravity_solves() const { return gravity_solves_; }  // field computations (gravity_pass)
  // The largest h a particle may take (SpmhdOptions::h_max; +inf: none), and how many particles
  // sit there at the last solve (their root of (4)-(5) lies beyond).
  Real h_cap() const;
  std::size_t smoothing_lengths_at_cap() const;
  // Sum of interacting_pairs() over all RHS evaluations so far.
  double pair_interactions_total() const { return pairs_total_; }

  // Per-particle quantities of the most recent rhs() (or evaluate()), in particle (state) order.
  const std::vector<Real>& h() const { return in_particle_order(h_, 1, out_h_); }
  const std::vector<Real>& rho() const { return in_particle_order(rho_, 1, out_rho_); }
  const std::vector<Real>& omega() const { return in_particle_order(omega_, 1, out_omega_); }
  const std::vector<Real>& pressure() const { return in_particle_order(P_, 1, out_P_); }
  const std::vector<Real>& div_b() const { return in_particle_order(divB_, 1, out_divB_); }  // seed 000, eq. (20)
  const std::vector<Real>& div_v() const { return in_particle_order(divv_, 1, out_divv_); }  // continuity form, eq. (25)
  const std::vector<Real>& magnetic_field() const { return in_particle_order(B_, 3, out_B_); }  // 3 x N
  const std::vector<Real>& positions() const { return in_particle_order(x_, D, out_x_); }  // D x N (fixed, or last state)
  Real cleaning_speed() const { return cleaning_speed_; }  // global c_h (the largest if local_ch)
  const std::vector<Real>& cleaning_speeds() const {  // c_h,a
    return in_particle_order(cleaning_speeds_, 1, out_cleaning_speeds_);
  }

  // Self-gravity of the most recent rhs() (or evaluate()): the potential energy (1/2) sum m Phi
  // (self terms included; 0 without gravity) and the potentials per unit mass, particle order.
  Real potential_energy() const { return potential_energy_; }
  // Sink particles (options().sink_particles): their count in the state.
  std::size_t sinks() const { return layout_.particles(Species::Sink); }
  // A new particle set between steps: the gas particles kept[i] (old numbering, ascending or in
  // any order) become particles i, and the state holds `sinks` sink particles. Their h (the
  // last iterates) and div v carry over as the next solve's start; the neighbour lists are
  // rebuilt at the next evaluation. The caller moves the state (resize_species) and the stepper
  // (Stepper::resize). With kept a permutation: the state re-sorted.
  void change_particles(const std::vector<std::size_t>& kept, std::size_t sinks);

  // Restart (ode_system.hpp): each h solve starts Newton from the previous h, so the converged h
  // depends on that start at the tolerance's round-off; the checkpoint carries it. resume_data()
  // is the last iterate of each solve (particle order; h() is one Newton step past it); resume(h)
  // sets the starts (positive and finite, one per gas particle) and rebuilds the lists at the next
  // evaluation, whose solve then repeats the interrupted run's last sums and Newton step: its h,
  // rho and Omega at the checkpoint, bit for bit. With predict_h, after a force pass, the iterates
  // are followed by div_v() and the time of h (2 N + 1 values), so that the next solve starts from
  // the same predicted guesses as the uninterrupted run's; resume takes N values (an older
  // checkpoint) or 2 N + 1.
  std::vector<Real> resume_data() const override;
  void resume(std::span<const Real> data) override;
  ResumeShape resume_shape() const override;

  // The momentum budget of the RHS at y (diagnostics; refreshes the scheme at y, evaluate()):
  // `total` = sum_a m_a dv_a/dt over gas and sinks, and `tensile` its part from the tensile-
  // instability correction (seed 000, eq. (9)): -sum_a m_a B_a S_a, S_a the symmetric divergence
  // sum_b m_b [B_a/(Omega_a rho_a^2) . grad W_ab(h_a) + B_b/(Omega_b rho_b^2) . grad W_ab(h_b)]
  // (0 without the correction). Every other term conserves momentum (equal and opposite pair
  // forces, the dual-tree gravity), so total - tensile is round-off. NaN when y cannot be evaluated.
  struct MomentumBudget {
    Vec<D> total = Vec<D>::Zero(), tensile = Vec<D>::Zero();
  };
  MomentumBudget momentum_budget(Real t, const Real* y);

  // The barotropic EOS (options().barotropic), or nullptr for the adiabatic gas.
  const BarotropicEos* barotropic_eos() const { return eos_ ? &*eos_ : nullptr; }
  const std::vector<Real>& potential() const { return gravity_potential_; }

  // rhs() into an internal buffer, to refresh the per-particle quantities above; nothing when y
  // is the state of the last evaluate() and nothing ran since (a function of (t, y)).
  int evaluate(Real t, const Real* y) noexcept;
  // Whether the last evaluation, rhs() or an rhs_subset() of every particle, was at y's
  // positions (gas and sinks) and no particle moved, left or came since (serial schemes): h,
  // rho, Omega and the potentials above are y's then, div v that of the velocities that
  // evaluation saw (a leapfrog's prediction).
  bool fully_evaluated_at_positions_of(const Real* y) const;

 private:
  int prepare(Real t, const Real* y);              // neighbours, density, P, c, B, c_h
  // 0, or 1 (recoverable, error_ says why) when h cannot be solved or outgrows the box.
  int ensure_neighbours_and_density(Real t, const Real* x);  // src/schemes/spmhd/spmhd_density.cpp
  void predict_smoothing_lengths(Real t);  // the solve's initial guesses at t (spmhd_density.cpp)
  static Real list_growth_for_attempt(int attempt);  // spmhd_density.cpp
  Real half_period() const;  // half the shortest periodic side of the box (+inf: none)
  void slots_to_solve();  // solve_slots_: the slots prepare() must solve, of those it serves
  bool served_slots_solved_at(Real t);  // prepare(): nothing to solve at x_ for the served slots at t
  // slots: the slots (memory rows) of the gas particles among `particles`, in their order (sinks skipped)
  void slots_of(std::span<const std::size_t> particles, std::vector<std::uint32_t>& slots);
  void densities_of_predicted_h();  // SubsetDensity::Predicted: rho of the unsolved slots from their h
  void set_h_time(Real t);  // every slot's h solved at t
  // lists for list_h_ (grow_only: no list shorter than the last build's), then slots in cell order
  int build_neighbours(const Real* x, bool grow_only = false);
  struct DensityStats {
    std::size_t not_converged = 0, outside_list = 0, iterations = 0, capped = 0;
    Real h_max = 0;
  };
  // the slots `only` (all when null); h_[i] <= list_h_served_[i]; sets list_h_needed_
  DensityStats solve_density(const Real* x, const std::vector<std::uint32_t>* only = nullptr);
  void euler_potential_field(const Real* x, const Real* alpha);
  void pair_loop_arrays(const Real* y);            // the per-particle arrays of force_pass
  // The pair loops over the slots `only` (ascending), or all slots when null.
  void force_pass(const Real* y, Real* ydot, const std::vector<std::uint32_t>* only = nullptr);  // spmhd_forces.cpp
  const Real* tensile_weights(const Real* y);  // per slot: the share of eq. (9) applied; nullptr: all of it everywhere
  void gravity_pass(Real* ydot, const std::vector<std::uint32_t>* only = nullptr);  // spmhd_gravity.cpp
  void compute_gravity(const std::vector<std::uint32_t>* only);                     // the field, into gravity_acc_
  void note_full_evaluation(const Real* y);
  void sink_pass(const Real* y, Real* ydot);       // src/schemes/spmhd/spmhd_sinks.cpp
  void allocate_per_particle();
  void remove_particles(const std::vector<std::size_t>& kept, std::size_t sinks);  // change_particles' removals
  // zeta_a of the grad-h term from a density solve's candidates (spmhd_density.cpp)
  static Real gravitational_zeta_of(const Real* r, const Real* m, std::size_t count, int lanes, Real m_a, Real h_a,
                                    Real rho_a);
  Real force_time_step(const Real* ydot) const;    // min force_courant sqrt(h / |dv/dt|)
  Real force_step(std::size_t slot, const Real* ydot) const;  // force_courant sqrt(h / |dv/dt|) of one slot
  // C h / v_sig of one slot, v: velocities in slot order (v_) or null (+inf without a signal speed;
  // NaN, with error_, for a non-finite one)
  Real courant_step(std::size_t slot, const Real* v);  // finite_courant_step; a NaN named in error_
  Real own_step(std::size_t slot, const Real* ydot);   // min(courant_step, force_step with self-gravity)
  // prepare(t, y) for the per-particle steps, and the accelerations they read: ydot, or with
  // self-gravity and no ydot f(t, y) evaluated (ydot then points to it); nonzero with error_ set.
  int prepare_steps(Real t, const Real* y, const Real*& ydot) noexcept;
  Real finite_courant_step(std::size_t slot, const Real* v) const;  // NaN where a speed or h is not finite

  // The per-slot array `slots` (comps per particle) in particle order, cached per RHS.
  struct ParticleOrderCache {
    std::vector<Real> data;
    long version = -1;
  };
  const std::vector<Real>& in_particle_order(const std::vector<Real>& slots, int comps, ParticleOrderCache& c) const;
  void sort_slots_by_cell();  // after a list build: renumber slots in cell order

  std::size_t n_;
  // Slots 0 .. n_ - 1 hold this rank's particles, n_ .. n_all_ - 1 the halo (distributed runs;
  // n_all_ = n_ serially). Per-slot arrays that neighbours read (x_, h_, ms_, rho_, ...) have
  // n_all_ entries; those of the own particles only (h_eval_, divv_, list_h_, ...) n_.
  std::size_t n_all_ = 0;
  std::unique_ptr<spmhd_detail::Halo<D>> halo_;  // distributed runs
  bool h_unset_ = false;                         // no h yet: the first guess from the bounding box
  bool solved_ = false;  // distributed: h_, rho_, omega_ of the local particles solved at x_ (lists maybe not)
  // Distributed parts (spmhd_distributed.cpp).
  int distributed_prepare_positions(Real t, const Real* y);   // collective: halo, lists, density
  int distributed_density_attempt(Real t, const Real* y, int attempt, std::string& message);
  void resize_slots(std::size_t all);                          // n_all_ after a new halo plan
  // Collective, before a force pass: the halo's v, u, B, psi (and h, rho, Omega after a solve),
  // then their P, c, fast speeds and c_h.
  void exchange_halo_fields(const Real* y);
  bool halo_density_stale_ = false;                            // a solve since the last exchange
  std::vector<Real> local_density_;                            // h, rho, Omega per particle (exchange)
  Real equation_of_state(std::size_t begin, std::size_t end);  // P, c, c_f of slots; the largest c_f
  void set_cleaning_speeds(std::size_t begin, std::size_t end);  // spmhd_cleaning_speeds.cpp
  void spread_cleaning_speeds();                                  // SpmhdOptions::ch_spread
  std::vector<std::uint8_t> spread_hops_;                         // its scratch: hops from a read slot
  std::vector<Real> spread_next_;
  const std::uint32_t* slot_keys() const;                      // rows' sort keys: global ids per slot
  const Real* particle_positions(const Real* y) const;         // this rank's, particle order (state or fixed)
  std::vector<Real> all_fixed_x_, fixed_x_;                    // distributed fixed particles: every one's, this rank's
  // h_ from the bounding box of every rank's positions x (collective when distributed), on
  // this rank if `apply`
  void first_smoothing_lengths(const Real* x, bool apply);
  std::vector<Real> new_radius_, plan_radius_;                 // distributed: particle order
  std::vector<Real> m_;     // masses, particle order
  std::vector<Real> ms_;    // masses, slot order
  std::vector<std::uint32_t> perm_, order_;  // slot -> particle; scratch of sort_slots_by_cell
  std::vector<std::uint32_t> key_;           // distributed: slot -> global id
  std::vector<Real> permute_scratch_;
  std::vector<Real> x_from_state_, v_, u_, psi_, alpha_;  // inputs gathered from the state (slot order)
  long version_ = 0;                                      // bumped by every prepare()
  mutable ParticleOrderCache out_h_, out_h_eval_, out_rho_, out_omega_, out_P_, out_divB_, out_divv_, out_B_, out_x_,
      out_cleaning_speeds_;
  SpmhdOptions opt_;
  StateLayout layout_;
  // the cell grid, or a kd-tree when the list radii span decades (a collapse): neighbours/neighbour_method.hpp
  AdaptiveNeighbourSearch<D> ns_;
  bool built_ = false;
  // x_: the fixed positions, or those of the last prepare() (the density solve is skipped when the
  // state's positions equal them bit for bit). Slot order, as all below.
  std::vector<Real> x_;
  std::vector<Real> h_, rho_, omega_, P_, sound_speed_, fast_speed_, B_, divB_, divv_;
  Real t_h_ = 0;               // the time of the state h_ was solved for (all slots)
  // Subset evaluations (rhs_subset) solve the slots their rows read only: per slot the time its h
  // was solved at, and whether it is solved at x_; the particles prepare() serves (empty: all).
  std::vector<Real> t_h_slot_;
  std::vector<char> solved_at_x_;
  bool every_slot_solved_ = false;  // since the particles last changed (allocate_per_particle)
  std::span<const std::size_t> serve_particles_;
  std::vector<std::uint32_t> solve_slots_;
  std::vector<char> solve_wanted_;
  Real t_ensured_ = std::numeric_limits<Real>::quiet_NaN();  // the last ensure_neighbours_and_density's t
  bool rate_known_at_ensure_ = false;                        // ... and its h_rate_known_
  bool h_rate_known_ = false;  // divv_ is from a force pass after the last solve (predict_smoothing_lengths)
  std::vector<Real> tensile_weight_;  // tensile_weights
  std::vector<Real> cleaning_speeds_;  // c_h,a (all equal to cleaning_speed_ unless local_ch)
  std::vector<Real> scratch_;
  std::vector<Real> subset_scratch_;           // rhs_subset: the sink forces of all particles
  std::vector<std::size_t> entry_owner_;       // rhs_subset: entry_particles() for the counts below
  std::pair<std::size_t, std::size_t> entry_owner_counts_{~std::size_t{0}, 0};  // (gas, sinks) it was made for
  std::vector<char> is_active_;                // rhs_subset: per particle
  std::vector<std::uint32_t> active_slots_;    // rhs_subset: the active gas particles' slots
  std::vector<std::uint32_t> slot_of_;         // slots_of: particle -> slot
  std::vector<std::uint32_t> served_slots_;    // slots_of's answer for the served particles
  std::vector<Real> own_of_slot_, active_steps_;   // active_stable_dt
  std::vector<std::uint32_t> limiter_near_;        // its neighbours within reach of one active row
  // The interacting neighbours of each row of the last subset force pass (rows in active_slots_'s
  // order), for active_stable_dt at the same state; interacting_rows_valid_ until x, h or the
  // slots change (prepare, remove_particles) or a full force pass runs.
  std::vector<std::vector<std::uint32_t>> interacting_rows_;
  bool interacting_rows_valid_ = false;
  std::span<const std::uint32_t> neighbours_within_reach(std::size_t a, const MinimumImage<D>& image);
  int own_steps_by_slot(Real t, const Real* y, const Real* ydot);
  Real least_neighbour_step(std::size_t a, const MinimumImage<D>& image) const;
  std::vector<Real> evaluated_y_;  // the state of the last evaluate(), valid while version_ == evaluated_version_
  long evaluated_version_ = -1;
  bool full_rhs_at_x_ = false;         // the last evaluation was of every particle at x_ (fully_evaluated_at_positions_of)
  std::vector<Real> full_rhs_sink_x_;  // the sinks' positions at that evaluation
  long gravity_solves_ = 0;
  std::vector<Real> self_potential_;   // the last full compute_gravity's potentials, before the sinks' part
  Real self_potential_energy_ = 0;     // and its energy
  // Per-particle factors of the pair loop (init): one record per particle of what its neighbours
  // read (src/schemes/spmhd/spmhd_pair_row.hpp: x, h, m, 1/h, 1/h^(D+2), rho, P, u, c_f,
  // psi/(Omega rho^2), psi, B, v, M/(Omega rho^2) (seed 000 eq. (8)), B/(Omega rho^2)), and 1/(Omega rho^2).
  std::vector<Real> records_, inv_omega_rho2_;
  std::vector<std::uint32_t> row_scratch_;  // per thread: a row's interacting neighbours
  std::vector<Real> h_guess_;       // h at the start of the density solve
  std::vector<Real> h_eval_;        // the last iterate of each h solve (h_ is one Newton step past it)
  // Per-particle Verlet lists: particle i's list radius is support * [list_h_[i] (1 + f skin) +
  // (1 - f) skin min list_h_] (f = SpmhdOptions::skin_own_fraction; a pair is listed if closer than the larger of its two radii); list_h_served_[i], the largest
  // h the lists serve now; list_h_needed_[i] > 0: the h the next build must serve (an h grew past
  // list_h_served_[i]).
  std::vector<Real> list_h_, list_h_served_, list_h_needed_, radii_;
  // lists_serve: whether the lists hold every pair at x (the Verlet rule, a few fast movers apart)
  static constexpr std::size_t kFastMovers = 32;
  bool lists_serve(const Real* x);
  bool serve_against(Real partner, const std::uint8_t* fast);
  bool fast_movers_listed(const Real* x);
  std::vector<Real> displacement_;             // since the last build, per slot
  std::vector<std::uint32_t> fast_movers_;     // the slots that moved most
  std::vector<std::uint8_t> is_fast_mover_, in_row_;
  std::vector<Real> cand_;          // per-thread candidate (r^2, r, m) of the density solve
  std::size_t max_list_ = 0;        // longest neighbour list of the current build
  std::size_t interacting_pairs_ = 0;
  double pairs_total_ = 0, h_iterations_ = 0;
  long density_solves_ = 0;
  // How far a list grows for an h beyond it, per attempt of a solve (list_growth_for_attempt).
  Real list_growth_ = 1.5;
  Real cleaning_speed_ = 0;         // global c_h (the largest c_h,a with local_ch)
  // Self-gravity (opt_.self_gravity): the solver; its sources' positions and h, accelerations
  // (D x n) and potentials in particle order (spmhd_gravity.cpp says why); zeta_a / Omega_a of
  // the grad-h term, slot order.
  std::optional<BarotropicEos> eos_;  // opt_.barotropic
  std::unique_ptr<SelfGravity> gravity_;
  std::vector<Real> gravity_x_, gravity_h_, gravity_acc_, gravity_potential_, zeta_over_omega_;
  std::vector<std::uint8_t> gravity_wanted_;  // the tree's targets of a subset
  std::size_t entries_within_reach(std::size_t a, const MinimumImage<D>& image, std::vector<std::uint32_t>& near,
                                   Real slack = 1e-12) const;
  GravitySources gravity_sources() const { return {gravity_x_.data(), m_.data(), gravity_h_.data(), n_}; }
  SinkGasGravity<K> sink_gas_;          // sink-gas gravity (opt_.sink_particles)
  std::vector<Real> sink_acc_, gas_from_sinks_, sink_potential_;
  Real potential_energy_ = 0;
  long rhs_calls_ = 0;
  long builds_ = 0;
  std::string error_;
};

}  // namespace sphark
