// Leapfrog steppers, one class, two variants (both fixed dt or dt = cfl_safety x max_stable_dt).
// The next step's max_stable_dt is taken right after each step (plan_next_step), before the time
// loop's after_step: a resize that carries the derivatives along (gas accreted onto a sink, a
// migration) keeps it and the next kick's derivative, so that no evaluation follows it (Phantom
// takes its next step from the force pass before it accretes, and kicks on with those forces).
//
// "leapfrog": kick-drift-kick, one RHS evaluation per step (FSAL, Phantom style). With w every
// entry except the positions x (velocity, density, energy, B, psi, ...):
//   w_half  = w_n + dt/2 ẇ_n                  (kick)
//   x_{n+1} = x_n + dt v_half                 (drift)
//   w*      = w_half + dt/2 ẇ_n               (predictor for the velocity-dependent RHS)
//   ẇ_{n+1} = f(t_{n+1}, x_{n+1}, w*)
//   w_{n+1} = w_half + dt/2 ẇ_{n+1}           (kick)
// It kicks the continuity density like a velocity, with dρ/dt = Σ m v_ab·∇W_ab evaluated at the
// start velocity and at the PREDICTED end velocity w*: the map is not time-reversible and its
// energy error grows over periods (docs/time_integration.md).
//
// "leapfrog-rev": kick-drift-kick in which only v is kicked; every other entry q (ρ, u, B, ψ)
// is advanced in the drift together with x, by the midpoint rule along the straight drift path.
// Two RHS evaluations per step:
//   v_half  = v_n + dt/2 a_n                              (kick)
//   x_mid   = x_n + dt/2 v_half,  q* = q_n + dt/2 q̇_n     (q* only for a q-dependent q̇)
//   q_{n+1} = q_n + dt q̇(x_mid, v_half, q*)               (drift of q, midpoint rule)
//   x_{n+1} = x_n + dt v_half                             (drift of x)
//   a_{n+1} = a(x_{n+1}, v_half + dt/2 a_n, q_{n+1})
//   v_{n+1} = v_half + dt/2 a_{n+1}                       (kick)
// For constant-h continuity-density WCSPH without diffusion, viscosity and cleaning, dρ_a/dt =
// Σ_b m_b v_ab·∇W_ab = d/dt Σ_b m_b W_ab(x) (seed 000, eq. (28)): ρ is a function of x (plus a
// constant), the system is Hamiltonian, and this step is time-reversible (v -> -v maps the step
// onto its inverse: q̇ is odd in v and independent of q, a is independent of v). Where q̇
// depends on q (δ-SPH, ψ damping) or a on v (viscosity) it is reversible only up to O(dt^3) of
// the predictors.
#include "leapfrog_stepper.hpp"

namespace sphark::detail {

std::unique_ptr<Stepper> make_leapfrog_stepper(OdeSystem& system, const StepperOptions& opts,
                                               Real t0, const Real* y0) {
  return std::make_unique<LeapfrogStepper>(system, opts, t0, y0, opts.method == "leapfrog-rev");
}

}  // namespace sphark::detail
