#pragma once
// A small distributed SPH system that exercises the whole distributed design on a real SPH
// operator: periodic 2D box, fixed per-particle h (varying in space, so pairs are found
// within max(r_a, r_b)), density by summation and the symmetric pressure force with a
// Monaghan viscosity. State per particle: x (2), v (2); mass and h ride along (migrate).
//
// The right-hand side follows the order a scheme must use (docs/scaling.md):
//   1. halo plan: rebuilt when still_valid() fails (collective), then m and h of the halo;
//   2. exchange x, v of the halo (collective);
//   3. neighbour lists over local + halo, rows sorted by global id (local);
//   4. density  rho_a = sum_b m_b W(r_ab, h_ab), h_ab = (h_a + h_b) / 2  (seed 000, eq. (4)
//      with the symmetrised h); pressure by the Tait EOS (seed 000, eq. (26)) (local);
//   5. agree on the local outcome (collective: a failure stops every rank here, before the
//      next exchange);
//   6. exchange rho and P of the halo (collective);
//   7. forces: seed 000, eq. (27) plus Monaghan (1992) viscosity, local particles only.
// With rows sorted by global id every sum runs over the same terms in the same order on any
// number of ranks, so a distributed run reproduces the serial one bit for bit.
#include <cstdint>
#include <string>
#include <vector>

#include "sphark/integrate/ode_system.hpp"
#include "sphark/neighbours/neighbour_search.hpp"
#include "sphark/parallel/halo.hpp"

namespace sphark::testing {

struct SphDemoParams {
  Real rho0 = 1;
  Real sound_speed = 10;
  Real alpha = 0.1;  // Monaghan viscosity
  Real skin_h = 0.1; // Verlet skin of the halo plan, in units of the smallest h
};

class SphDemo final : public OdeSystem {
 public:
  SphDemo(Communicator comm, PeriodicBox<2> box, SphDemoParams p);

  // The particles this rank holds (their state is passed to the stepper separately).
  void set_particles(std::vector<std::int64_t> ids, std::vector<Real> mass, std::vector<Real> h);
  const std::vector<std::int64_t>& ids() const { return ids_; }
  std::vector<std::int64_t>& ids() { return ids_; }
  std::vector<Real>& mass() { return m_; }
  std::vector<Real>& smoothing_length() { return h_; }
  std::size_t count() const { return ids_.size(); }

  std::size_t size() const override { return 4 * ids_.size(); }
  int rhs(Real t, const Real* y, Real* ydot) noexcept override;
  std::size_t position_offset() const override { return 0; }
  std::size_t velocity_offset() const override { return 2 * ids_.size(); }
  std::size_t position_size() const override { return 2 * ids_.size(); }
  Real max_stable_dt(Real t, const Real* y, const Real* ydot) noexcept override;
  std::string last_error() const override { return error_; }

  // Density of the local particles at the last rhs().
  std::vector<Real> density() const { return {rho_.begin(), rho_.begin() + static_cast<long>(count())}; }
  const HaloPlan<2>& halo() const { return plan_; }

 private:
  void gather_halo(const Real* y);
  int density_and_pressure();
  void forces(Real* ydot) const;

  Communicator comm_;
  PeriodicBox<2> box_;
  SphDemoParams p_;
  std::vector<std::int64_t> ids_;
  std::vector<Real> m_, h_;
  HaloPlan<2> plan_;
  bool plan_built_ = false;
  NeighbourSearch<2> search_;
  // Local + halo arrays (local first).
  std::vector<Real> x_, v_, m_all_, h_all_, r_all_, rho_, p_all_;
  std::vector<std::uint32_t> keys_;
  std::string error_;
};

}  // namespace sphark::testing
