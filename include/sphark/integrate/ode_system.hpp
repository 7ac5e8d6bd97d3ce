#pragma once
// The contract between a physics scheme and every time stepper (ARKODE ERK, ARKODE IMEX,
// leapfrog). A scheme sees only raw arrays laid out by its StateLayout; it never sees SUNDIALS.
//
// Every callback is a function of its arguments (t, y [, ydot]) alone: what a scheme derives
// from y (neighbour lists, density, h, ghosts) it recomputes, or reuses only when it is provably
// the same (e.g. memoised on the exact content of y). Nothing a callback returns depends on
// which callback ran before, with one admitted exception: an iterative solve may start from its
// previous answer (the h of SPMHD and of the ghost-wall WCSPH: Newton from the last h), and its
// converged answer then depends on that start at the solve's round-off. Such a system returns
// the start as resume_data(), the checkpoints carry it, and resume() restores it, so that a
// restart continues bit for bit.
#include <cstddef>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "sphark/core/types.hpp"

namespace sphark {

class StateLayout;

class OdeSystem {
 public:
  virtual ~OdeSystem() = default;

  // Length of the state vector.
  virtual std::size_t size() const = 0;
  // The layout of the state (species, fields), for the guard's checks and messages; nullptr for
  // a plain ODE without particles (the guard then checks finiteness only).
  virtual const StateLayout* state_layout() const { return nullptr; }

  // Full right-hand side ydot = f(t, y).
  virtual int rhs(Real t, const Real* y, Real* ydot) = 0;

  // IMEX split: the stiff part is diagonal and linear, f_I(y)_k = -c_k y_k with c_k >= 0 (e.g.
  // psi damping -psi/tau). f_E = f - f_I. Systems without a stiff part return false.
  virtual bool has_stiff_diagonal() const { return false; }
  virtual int stiff_diagonal(Real /*t*/, const Real* /*y*/, Real* /*c*/) { return -1; }

  // Leapfrog (kick-drift-kick) needs to know which block is position and which is velocity:
  // x = y[position_offset() .. + position_size()), v = y[velocity_offset() .. + position_size()).
  // Every other entry is "kicked" like the velocity.
  virtual std::size_t position_offset() const { return 0; }
  virtual std::size_t velocity_offset() const { return 0; }
  virtual std::size_t position_size() const { return 0; }

  // Largest stable step at (t, y) (CFL, force and any other criteria), used by the leapfrog for
  // its step and by adaptive runs as a cap. ydot, when not null, is f(t, y) or the stepper's
  // approximation of it (the leapfrog passes the derivative its next kick uses); with null the
  // system derives what it needs from y itself. Returns a positive step, +inf when the system
  // has no such limit, or NaN on failure (last_error() says why): the stepper then stops with
  // that failure instead of taking an uncapped step.
  virtual Real max_stable_dt(Real /*t*/, const Real* /*y*/, const Real* /*ydot*/) {
    return std::numeric_limits<Real>::infinity();
  }

  // Event (root) functions g_k(t, y); a sign change stops the integration at the root.
  virtual int num_roots() const { return 0; }
  virtual int roots(Real /*t*/, const Real* /*y*/, Real* /*g*/) { return 0; }

  // Human-readable reason of the last non-zero return (for the run summary).
  virtual std::string last_error() const { return {}; }

  // Restart: what the next call starts from besides (t, y) (see the top of this file), e.g. the
  // previous h of every particle, in particle order; empty: nothing. resume(data) with what
  // resume_data() returned restores it before the restarted run's first step; empty data (an
  // older checkpoint) keeps the system's own start. resume throws std::invalid_argument for
  // data that does not fit (wrong length, non-physical values).
  virtual std::vector<Real> resume_data() const { return {}; }
  virtual void resume(std::span<const Real> /*data*/) {}
  // The shape of resume_data(): `per_particle` blocks of one value per particle (value k of
  // particle a at k n + a), then `tail` values that do not belong to a particle. A distributed
  // run's checkpoint gathers the blocks by global id (run/time_loop_checkpoint.cpp). Default:
  // no per-particle blocks (such data cannot be checkpointed distributed).
  struct ResumeShape {
    int per_particle = 0, tail = 0;
  };
  virtual ResumeShape resume_shape() const { return {}; }

  // --- Particles: the unit of work (StepperStats::particle_evals) and of multirate stepping.
  // Particles are numbered 0 .. num_particles()-1, species after species in layout order.
  // Default: every particle of the layout; a plain ODE without a layout is one particle.
  virtual std::size_t num_particles() const;

  // The particle owning each state entry (size() entries), for steppers that advance particles
  // by steps of their own (block steps). Default: from the layout (species after species); a
  // plain ODE's entries all belong to its one particle.
  virtual std::vector<std::size_t> entry_particles() const;

  // Multirate (issue #17): true if rhs_subset() and particle_stable_dt() are implemented.
  virtual bool supports_subsets() const { return false; }
  // Derivatives of the particles `active` (ascending, unique) at (t, y): every entry of an active
  // particle receives f(t, y) for that entry, computed against every neighbour (active or not);
  // every other entry of ydot is set to 0, so that rhs_subset(A) + rhs_subset(complement of A)
  // == rhs() (up to the round-off of the sum). Work proportional to the active set where the
  // scheme allows it. A function of (t, y, active) alone, like every callback (see above).
  // Return codes as rhs(). Default: throws std::logic_error (not supported).
  virtual int rhs_subset(Real /*t*/, const Real* /*y*/, std::span<const std::size_t> /*active*/,
                         Real* /*ydot*/) {
    throw std::logic_error("rhs_subset: this system cannot evaluate a subset of its particles");
  }
  // Each particle's own largest stable step at (t, y) (num_particles() entries in dt): the
  // per-particle analogue of max_stable_dt, with the same ydot convention (f(t, y) or the
  // stepper's approximation of it, or null: derived from y); +inf: no limit. 0 success,
  // non-zero failure (last_error() says why). Default: throws std::logic_error (not supported).
  virtual int particle_stable_dt(Real /*t*/, const Real* /*y*/, const Real* /*ydot*/, Real* /*dt*/) {
    throw std::logic_error("particle_stable_dt: this system reports no per-particle stable steps");
  }
  // Block steps (issue #17): the stable steps after an evaluation of the particles `active`
  // (ascending) at (t, y), ydot as above: an active particle's as particle_stable_dt gives it;
  // another particle's the bound that the active ones put on it (+inf where they put none; its
  // own step is the caller's, from its last evaluation). Default: particle_stable_dt, every
  // particle's own step at (t, y) (which bounds it too).
  virtual int active_stable_dt(Real t, const Real* y, const Real* ydot, std::span<const std::size_t> /*active*/,
                               Real* dt) {
    return particle_stable_dt(t, y, ydot, dt);
  }
};

}  // namespace sphark
