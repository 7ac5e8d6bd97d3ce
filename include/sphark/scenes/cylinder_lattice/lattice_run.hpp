#pragma once
// One run of the cylinder-lattice scene (seed 004, §8) and the low-resolution ensemble (§8.2):
//   t_max = min{t_final, t_penetration, t_accumulation}                   seed 004, eq. (37)
// The run stops at the first event of LatticeSystem (g_0: a particle crosses the wall, g_1: a
// ghost's support radius collapses) or at t_end; a blow-up (non-finite state, failed h solve)
// ends it with reason "failure: ..." (the system is wrapped in run/GuardedSystem).
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "sphark/integrate/stepper.hpp"
#include "sphark/scenes/cylinder_lattice/lattice.hpp"

namespace sphark {

struct LatticeRunConfig {
  LatticeParams params;        // mass and h_ref are set from `particles` by lattice_params()
  std::size_t particles = 100;
  unsigned seed = 1;           // random initial configuration
  Real min_separation = 0.7;   // of the random start, in units of the lattice spacing dx
  int relax_iterations = 200;  // then relaxed against the run's own ghosts (0: no relaxation)
  Real t_end = 10;
  StepperOptions stepper;      // default: leapfrog on the CFL step (see lattice_default_stepper)
};

struct LatticeRunResult {
  Real t_max = 0;
  std::string reason;  // "t_end", "penetration", "accumulation", "failure: ...", "stopped" (SIGINT/SIGTERM)
  StepperStats stats;
  long rhs_calls = 0;
  double cpu_seconds = 0;  // CPU time of the calling thread
  std::vector<Real> y;     // state at t_max
};

// The default stepper: kick-drift-kick leapfrog with dt = max_stable_dt (CFL + force criterion).
StepperOptions lattice_default_stepper();

// params with mass = rho0 * fluid area / n and h_ref = eta * dx (dx = lattice_spacing).
LatticeParams lattice_params(LatticeParams base, std::size_t n);

// n points in the fluid region (|x| >= R + dx/2), uniformly random with a minimum pairwise
// (minimum-image) distance min_separation * dx (random sequential addition, mt19937_64(seed)).
// Throws std::runtime_error if the points do not fit.
std::vector<Real> random_fluid_positions(const LatticeParams& p, std::size_t n, unsigned seed, Real min_separation);

// Called at t0, at every multiple of output_every and at t_max (after prepare(y): the system's
// density, h, ghosts are those of y).
using LatticeObserver = std::function<void(Real t, LatticeSystem& system, const Real* y)>;

// The initial positions of a run: random_fluid_positions, then at most relax_iterations steps of
// boundaries/wall_relaxation.hpp (node density with the ghosts of the run's own map, h = h_ref).
std::vector<Real> initial_positions(const LatticeRunConfig& cfg);

// Runs from rest at initial_positions(cfg). Never throws for a failing run (reason "failure: ...").
// After SIGINT/SIGTERM (run/signals.hpp) it ends at its next poll (set-up loops, every RHS
// evaluation) with reason "stopped". Steps below kStepFloorFraction x t_end end it as a failure.
LatticeRunResult run_lattice(const LatticeRunConfig& cfg, Real output_every = 0, const LatticeObserver& observe = {});

struct EnsembleJob {
  GhostMap map;
  Real v0;
  unsigned seed;
};

// Runs every job (cfg with its map, v0, seed) on `threads` threads, each run on one OpenMP
// thread; results[i] belongs to jobs[i] whatever the thread count (runs are independent and
// deterministic). on_done(i, result) is called under a lock after each run (may be empty).
// After SIGINT/SIGTERM (run/signals.hpp) no new run starts and the runs in progress end at their
// next poll with reason "stopped"; runs never started keep an empty reason.
std::vector<LatticeRunResult> run_ensemble(const LatticeRunConfig& cfg, const std::vector<EnsembleJob>& jobs,
                                           int threads,
                                           const std::function<void(std::size_t, const LatticeRunResult&)>& on_done = {});

std::string map_name(GhostMap map);  // "mirror" | "nonlinear"

}  // namespace sphark
