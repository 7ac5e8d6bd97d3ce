#pragma once
// Weakly compressible SPH (seed 000, §III-A) with constrained velocity divergence cleaning
// (seed 000, §III-B/C) as an OdeSystem. State: x, v, rho [, psi]. Constant h.
//
//   dx/dt   = v
//   dv/dt   = eq. (27) pressure + artificial viscosity + body force  - grad psi / rho  (eq. (39))
//   drho/dt = eq. (28) continuity (sign as eq. (36)) + density diffusion (delta-SPH)
//   dpsi/dt = -c_h^2 rho div v  (eq. (30), div v by eq. (36))  - psi / tau
// Energies and errors of a state: diagnostics/wcsph_diagnostics.hpp.
//
// Distributed runs (docs/scaling.md): after distribute(comm, ids) the system holds this rank's
// particles only (the state is theirs; global ids < 2^32) and every rhs() is collective: the
// halo of other ranks' particles within the support comes through HaloPlan exchanges
// (src/schemes/wcsph/wcsph_halo.hpp), the pair loops run for the local particles with rows
// sorted by global id, and the result equals the serial run's bit for bit.
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "sphark/integrate/ode_system.hpp"
#include "sphark/neighbours/neighbour_search.hpp"
#include "sphark/parallel/communicator.hpp"
#include "sphark/schemes/wcsph/wcsph_params.hpp"
#include "sphark/state/state_layout.hpp"

namespace sphark {

namespace wcsph_detail {
template <int D>
class Halo;
template <int D>
struct ParticleFields;
template <int D>
struct RowInput;
struct InsideRow;
template <int D>
struct ForceStore;
}  // namespace wcsph_detail

template <int D, class Kernel>
class WcsphSystem final : public OdeSystem {
 public:
  WcsphSystem(std::size_t particles, WcsphParams<D> params, std::optional<PeriodicBox<D>> box = std::nullopt);
  ~WcsphSystem() override;

  // Distributed: this rank holds the particles `ids` (size() becomes their state's); every
  // rhs() (and max_stable_dt without ydot) is then collective over comm, on any number of ranks.
  void distribute(Communicator comm, std::vector<std::int64_t> ids);
  // After a migration (distributed only): this rank's particles are now `ids`.
  void set_particles(std::vector<std::int64_t> ids);
  // Global ids of this rank's particles (empty unless distributed).
  const std::vector<std::int64_t>& ids() const;
  bool distributed() const { return halo_ != nullptr; }

  const StateLayout& layout() const { return layout_; }
  const WcsphParams<D>& params() const { return p_; }

  // OdeSystem
  std::size_t size() const override { return layout_.size(); }
  const StateLayout* state_layout() const override { return &layout_; }
  int rhs(Real t, const Real* y, Real* ydot) override;
  bool has_stiff_diagonal() const override { return p_.cleaning && p_.clean_sigma > 0; }
  int stiff_diagonal(Real t, const Real* y, Real* c) override;
  std::size_t position_offset() const override { return layout_.offset(Field::Position); }
  std::size_t velocity_offset() const override { return layout_.offset(Field::Velocity); }
  std::size_t position_size() const override { return layout_.field_size(Field::Position); }
  // CFL and force criteria at y; the force criterion uses ydot's accelerations, or evaluates the
  // RHS at y when ydot is null (memoised: no evaluation when y is the last state evaluated).
  Real max_stable_dt(Real t, const Real* y, const Real* ydot) override;
  std::string last_error() const override { return error_; }
  // Multirate (issue #17; src/schemes/wcsph/wcsph_subsets.cpp), serial systems only.
  bool supports_subsets() const override { return !halo_; }
  int rhs_subset(Real t, const Real* y, std::span<const std::size_t> active, Real* ydot) override;
  int particle_stable_dt(Real t, const Real* y, const Real* ydot, Real* dt) override;

  // Pressure and div v (eq. (36)) of state y: evaluates the RHS at y unless y is the state of the
  // last evaluation (bit for bit); the references stay valid until the next evaluation. The
  // first layout().particles() entries are the particles of y (distributed: then the halo's).
  const std::vector<Real>& pressure(Real t, const Real* y) { return evaluate(t, y), pressure_; }
  const std::vector<Real>& div_v(Real t, const Real* y) { return evaluate(t, y), div_v_; }

  long neighbour_builds() const { return builds_; }
  long rhs_calls() const { return rhs_calls_; }

 private:
  void resize_particles(std::size_t n);
  // Lists over `count` particles (local + halo; keys: global ids, or null serially), rebuilt
  // when `force` or a particle moved half the skin; slots in cell order, local ones first.
  void update_neighbours(const Real* x, std::size_t count, const std::uint32_t* keys, bool force);
  // rhs(): the pressures and the slot records (wcsph_detail::Record) of `count` particles.
  void fill_records(const wcsph_detail::ParticleFields<D>& f, std::size_t count);
  // rhs() up to the force loop: records, each local row's neighbours inside the support and,
  // for the corrected diffusion, the density gradients in the records.
  void prepare_rows(const wcsph_detail::ParticleFields<D>& f, std::size_t count);
  // rhs(): the force loop of the local particles into ydot.
  void forces(const Real* y, Real* ydot);
  wcsph_detail::ForceStore<D> force_store(const Real* y, Real* ydot);  // what a force row writes
  // Serial rhs() after fill_records: prepare_rows and forces in one pass (wcsph_one_pass.cpp).
  void rows_in_one_pass(const Real* y, Real* ydot);
  // rhs() of a distributed system (wcsph_distributed.cpp): prepare_rows and forces with the
  // halo's exchanges; the gradients of the halo from their owners.
  int distributed_rhs(const Real* y, Real* ydot);
  void exchange_gradients();
  wcsph_detail::RowInput<D> row_input() const;  // what the pair rows read (records_, lists)
  // Row a's neighbours inside the support: from inside_start(a) on (room: its list length + pad).
  static constexpr std::size_t kInsidePad = 8;
  void reserve_inside_rows();  // room for every local row's inside list
  std::uint32_t* inside_start(std::size_t a);
  wcsph_detail::InsideRow inside_row(std::size_t a) const;
  bool viscosity() const { return p_.alpha > 0 && !p_.cleaning_subsystem_only; }
  bool corrected_diffusion() const {
    return p_.delta * p_.h * p_.sound_speed > 0 && p_.diffusion_correction && !p_.cleaning_subsystem_only;
  }
  // rhs() at y into scratch_ unless y is evaluated_y_ (then nothing: every derived array is y's).
  void evaluate(Real t, const Real* y);
  Real max_acceleration(const Real* ydot) const;
  Real stable_dt(Real vmax, Real cmax, Real accel) const;

  WcsphParams<D> p_;
  StateLayout layout_;
  NeighbourSearch<D> search_;
  bool built_ = false;
  long builds_ = 0, rhs_calls_ = 0;

  // per particle, for the pair loops (src/schemes/wcsph/wcsph_pair_rows.hpp)
  std::vector<Real> pressure_, div_v_;
  // Slots: the pair loops' order, renewed at every list build in neighbour-grid cell order (a
  // scrambled particle order costs 3.4x at 10^5 particles); slot s is particle slot_particle_[s].
  std::vector<std::uint32_t> slot_particle_;
  std::vector<Real> records_;  // per slot: the fields its neighbours read (wcsph_detail::Record)
  std::vector<std::uint32_t> inside_;    // per RHS: each row's neighbours inside the support (at its list offset)
  std::vector<std::size_t> inside_count_;
  std::vector<Vec<D>> grad_rho_;
  std::vector<Real> grad_particles_;  // distributed: <grad rho> by particle, local + halo (exchanged)
  std::unique_ptr<wcsph_detail::Halo<D>> halo_;  // distributed only
  std::vector<Real> evaluated_y_, scratch_;  // the state of the last rhs(); its derivative buffer
  std::vector<std::uint32_t> slot_of_particle_, active_slots_;  // rhs_subset: the inverse of slot_particle_, active rows
  std::vector<char> read_slot_;                                 // rhs_subset: slots whose inside rows are read
  Real max_accel_ = 0;                       // max |dv/dt| of the last rhs()
  std::string error_;
};

}  // namespace sphark
