#pragma once
// Smoothed particle magnetohydrodynamics with constrained hyperbolic/parabolic divergence
// cleaning (seed 000, §II; Tricco & Price 2012). An OdeSystem: the state holds only what the
// variant needs (StateLayout):
//   evolve_particles:  x (D), v (D), u (1), then B (3) or Euler alpha (1), then psi (1) if cleaning
//   cleaning subsystem (fixed particles, §IV-A):  B (3), psi (1)
// Density, h and Omega come from summation each RHS (seed 000, eqs. (4)-(5)). The psi damping
// -psi/tau is the stiff diagonal c = sigma c_h / h_a on the psi entries.
//
// The RHS is gather-form (each particle sums its own neighbours; OpenMP over particles, no
// races, results independent of the thread count), and allocates nothing after the first call
// except when the Verlet lists must be rebuilt. Per-particle quantities of the pair loops are
// kept as structure-of-arrays, filled once per RHS (prepare()).
#include <optional>
#include <string>
#include <vector>

#include "sphark/integrate/ode_system.hpp"
#include "sphark/kernels/kernels.hpp"
#include "sphark/neighbours/neighbour_search.hpp"
#include "sphark/schemes/spmhd/spmhd_options.hpp"
#include "sphark/state/state_layout.hpp"

namespace sphark {

template <int D, class K = CubicSpline<D>>
class SpmhdScheme final : public OdeSystem {
 public:
  // masses: one per particle. fixed_positions (D x N, column-major) are required when
  // !opt.evolve_particles and ignored otherwise. Throws std::invalid_argument on bad input.
  SpmhdScheme(std::vector<Real> masses, SpmhdOptions opt, std::optional<PeriodicBox<D>> box = std::nullopt,
              std::vector<Real> fixed_positions = {});

  const StateLayout& layout() const { return layout_; }
  const SpmhdOptions& options() const { return opt_; }
  std::size_t particles() const { return n_; }
  const std::vector<Real>& masses() const { return m_; }

  std::size_t size() const override { return layout_.size(); }
  int rhs(Real t, const Real* y, Real* ydot) noexcept override;
  bool has_stiff_diagonal() const override { return opt_.cleaning != Cleaning::None && opt_.sigma > 0; }
  int stiff_diagonal(Real t, const Real* y, Real* c) noexcept override;
  std::size_t position_offset() const override;
  std::size_t velocity_offset() const override;
  std::size_t position_size() const override { return opt_.evolve_particles ? D * n_ : 0; }
  Real max_stable_dt(Real t, const Real* y) noexcept override;
  std::string last_error() const override { return error_; }

  // Number of RHS evaluations so far.
  long rhs_evaluations() const { return rhs_calls_; }
  // Number of neighbour-list builds so far (Verlet reuse: far fewer than RHS evaluations).
  long neighbour_builds() const { return builds_; }
  // The current neighbour lists (pairs within K::support * h (1 + skin) at the last build).
  const NeighbourSearch<D>& neighbours() const { return ns_; }
  // Pairs a-b (ordered, a != b) with |x_a - x_b| < K::support * max(h_a, h_b) at the last RHS:
  // the pair interactions the force loop evaluated.
  std::size_t interacting_pairs() const { return interacting_pairs_; }
  // Sum of interacting_pairs() over all RHS evaluations so far.
  double pair_interactions_total() const { return pairs_total_; }

  // Per-particle quantities of the most recent rhs() (or evaluate()).
  const std::vector<Real>& h() const { return h_; }
  const std::vector<Real>& rho() const { return rho_; }
  const std::vector<Real>& omega() const { return omega_; }
  const std::vector<Real>& pressure() const { return P_; }
  const std::vector<Real>& div_b() const { return divB_; }       // seed 000, eq. (20)
  const std::vector<Real>& div_v() const { return divv_; }       // continuity form, eq. (25)
  const std::vector<Real>& magnetic_field() const { return B_; }  // 3 x N (from state or potentials)
  const std::vector<Real>& positions() const { return x_; }       // D x N (fixed, or last state)
  Real cleaning_speed() const { return ch_; }                       // global c_h (the largest if local_ch)
  const std::vector<Real>& cleaning_speeds() const { return chs_; }  // c_h,a per particle

  // rhs() into an internal buffer, to refresh the per-particle quantities above.
  int evaluate(Real t, const Real* y) noexcept;

 private:
  int prepare(const Real* y);                      // neighbours, density, P, c, B, c_h
  void ensure_neighbours_and_density(const Real* x);  // src/schemes/spmhd/spmhd_density.cpp
  void build_neighbours(const Real* x, Real radius);
  struct DensityStats {
    std::size_t not_converged = 0, outside_list = 0;
    Real h_max = 0;
  };
  DensityStats solve_density(const Real* x, Real h_list);
  void euler_potential_field(const Real* x, const Real* alpha);
  void pair_loop_arrays(const Real* y);            // the per-particle arrays of force_pass
  void force_pass(const Real* y, Real* ydot);      // src/schemes/spmhd/spmhd_forces.cpp

  std::size_t n_;
  std::vector<Real> m_;
  SpmhdOptions opt_;
  StateLayout layout_;
  NeighbourSearch<D> ns_;
  bool built_ = false;
  std::vector<Real> x_;  // fixed positions, or a copy of the current ones
  std::vector<Real> h_, rho_, omega_, P_, cs_, cf_, chs_, B_, divB_, divv_;
  std::vector<Real> scratch_;
  // Pair-loop arrays (SoA): 1/h, 1/h^(D+2) (kernel gradient scale), o = 1/(Omega rho^2),
  // o M (the D x D block of the Maxwell stress, seed 000 eq. (8), times o), o B, o psi.
  std::vector<Real> hinv_, fscale_, o_, oM_, oB_, opsi_;
  std::vector<Real> cand_;          // per-thread candidate (r^2, r, m) of the density solve
  std::size_t max_list_ = 0;        // longest neighbour list of the current build
  std::size_t interacting_pairs_ = 0;
  double pairs_total_ = 0;
  Real ch_ = 0;
  long rhs_calls_ = 0;
  long builds_ = 0;
  std::string error_;
};

}  // namespace sphark
