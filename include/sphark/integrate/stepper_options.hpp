#pragma once
// Options and statistics shared by every time stepper (ARKODE ERK, ARKODE IMEX, leapfrog).
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/parallel/communicator.hpp"

namespace sphark {

inline constexpr int kStepsBelowFloor = 100;

struct StepperOptions {
  // Any explicit Butcher table of SUNDIALS 6.4.1 (see erk_table_names()), "ark-imex", "leapfrog"
  // or "mri-<MRI coupling table>" (multirate, see mri_table_names() in stepper.hpp).
  std::string method = "ARKODE_DORMAND_PRINCE_7_4_5";
  Real rtol = 1e-6;
  // Absolute tolerance: one value per state entry, or a single value for all; empty -> 1e-9.
  std::vector<Real> atol;
  // > 0: fixed step (ERK/IMEX: ARKODE fixed step, no error control; leapfrog: this dt).
  Real fixed_dt = 0;
  // Leapfrog without fixed_dt: dt = cfl_safety * system.max_stable_dt(t, y), every step.
  // Adaptive ARKODE runs: the step is bounded by cfl_safety * max_stable_dt evaluated at the
  // start of every advance() call (see stepper.hpp), unless cap_by_stability is false.
  Real cfl_safety = 1.0;
  // Adaptive ARKODE runs only: true bounds the step by cfl_safety * max_stable_dt (above);
  // false leaves the step to the error control alone (max_dt still applies), e.g. to measure
  // where the error control on its own loses stability. Leapfrog and fixed-step runs ignore it.
  bool cap_by_stability = true;
  // > 0: upper bound on every step of every method (except a fixed_dt run).
  Real max_dt = 0;
  // "leapfrog" only, > 0: Phantom's corrector iterations (step_leapfrog.f90, tolv). The RHS of a
  // KDK step sees predicted velocities v* (and B, psi, ... predicted alike); when the kicked
  // velocities differ from them by more than this (max over velocity entries |v - v*| / rms v),
  // the RHS is evaluated again at the kicked values and the kick redone, until they agree (the
  // trapezoidal rule for velocity-dependent terms; a step that does not converge in 30 is
  // retried at half the length). 0: off. (Phantom also bounds the next global step by the
  // first difference, dterr; not done here: docs/time_integration.md.)
  Real velocity_tolerance = 0;
  // > 0: first step of an adaptive ARKODE run (e.g. the last step of a run being restarted);
  // 0: ARKODE's own estimate. Ignored by fixed-step runs and the leapfrog.
  Real initial_dt = 0;
  // > 0: a step reduction after a recoverable RHS failure that would go below min_dt ends the
  // run (Failed) instead (otherwise a blow-up at time T can shrink steps towards T endlessly).
  Real min_dt = 0;
  // > 0: kStepsBelowFloor consecutive steps shorter than step_floor end the run (Failed, with
  // the state before the last of them); a step landing on an output time (it may be a sliver)
  // does not count. (Consecutive: ARKODE's first steps can lie orders of magnitude below the
  // stable step before its step control grows them, by up to 20x per step.) Whatever its
  // value, a step that does not advance t (t + dt == t) ends the run at once. The run driver
  // sets it from the run's time scale (run/time_loop.hpp: step_floor_fraction x t_end).
  Real step_floor = 0;
  // Polled before every right-hand-side evaluation and every leapfrog step: true ends advance()
  // with AdvanceStatus::Interrupted and the last accepted step in (t, y) (the time loop's stop
  // signals, run/signals.hpp). Empty: never. A distributed run polls it on every rank and
  // agrees on the answer (collective). The poll does not change a run that is not interrupted.
  std::function<bool()> interrupt;
  // Steppers whose particles take steps of their own ("leapfrog-blocks") call it at every event
  // inside a top step, after the kicks, with the time, the state there (every particle's
  // position at t; every entry of the `active` particles, those just evaluated and kicked, at t)
  // and the active particles: a system that removes some of them there (gas accreted onto a
  // sink, or made into a new sink) changes its particles and returns the new
  // state with, for each of its entries, the old entry it continues (entry_source; ~0 for every
  // entry of a new particle; the state does not grow), or nothing. The stepper carries its own
  // per-entry and per-particle data along, evaluates the new particles at (t, y), and goes on
  // with the top step. A top step that then fails or is interrupted rolls
  // back to its start: undo_removals() must give the system back the particles it had there.
  struct Removal {
    std::vector<Real> y;
    std::vector<std::size_t> entry_source;
  };
  std::function<std::optional<Removal>(Real t, const Real* y, const std::vector<std::size_t>& active)> remove_active;
  std::function<void()> undo_removals;
  // Called after remove_active with the state and active set after it: particles (any order)
  // that must end their steps at the next event, woken as a particle whose stable step fell is
  // (e.g. the neighbourhood of a sink candidate, which remove_active can turn into a sink only
  // when all of it is active). Empty: none.
  std::function<std::vector<std::size_t>(Real t, const Real* y, const std::vector<std::size_t>& active)> wake_next;
  // Restart: Stepper::resume_data() of the run being continued (see stepper.hpp); empty = none.
  std::vector<Real> resume_data;
  // Testing aid of the blow-up path: from this time on the guard (integrate/guarded_system.hpp)
  // makes every derivative non-finite. +inf: never.
  Real inject_nan_from = std::numeric_limits<Real>::infinity();
  // Internal steps allowed per advance() call (ARKODE's default is 500).
  long max_steps = 1000000;
  // ARK IMEX pair of ARKODE 6.4.1: ARK324L2SA (order 3), ARK436L2SA (4), ARK437L2SA (4),
  // ARK548L2SA (5), ARK548L2SAb (5).
  std::string imex_table = "ARK436L2SA";
  // Multirate (issue #17), method "mri-<coupling table>" (mri_table_names()), fast integrator
  // an explicit ARKStep with mri_fast_table (any ERK table, see erk_table_names()). MRIStep of
  // SUNDIALS 6.4.1 takes fixed slow steps; repartitioned before every slow step:
  //  - fixed_dt > 0: the slow step is fixed_dt, the fast step fixed_dt / mri_ratio; particles
  //    whose stable step (x cfl_safety) is below fixed_dt are fast;
  //  - else max_dt > 0: the particles are binned on the power-of-two levels of max_dt; the slow
  //    step is the level holding (with the shallower ones) mri_slow_fraction of the particles,
  //    the deeper ones are fast, the fast step is the deepest level's (at least slow / mri_ratio);
  //    MRIStep restarts when these steps change.
  // mri_levels > 2 nests MRISteps (mri_stepper.cpp): level k steps by fixed_dt / mri_ratio^k
  // (mri_ratio >= 2), or, adaptive, the power-of-two levels from the slow level to the deepest are
  // shared out evenly among the fast MRI levels (mri_split.hpp).
  // A particle moves to a longer step only when its stable step exceeds it by the factor
  // (1 + partition_hysteresis) (also the block steps of "leapfrog-blocks").
  int mri_ratio = 4;
  int mri_levels = 2;
  std::string mri_fast_table = "ARKODE_ZONNEVELD_5_3_4";
  Real mri_slow_fraction = 0.9;
  Real partition_hysteresis = 0.25;
  // "leapfrog-blocks": instead of top steps of max_dt (the last shortened to land on t_out), the
  // way to t_out in m equal top steps (each <= max_dt), m chosen at each cycle's start for the
  // fewest particle evaluations at the particles' stable steps (the power-of-two ladder shifted
  // to fit them); every cycle then bins afresh.
  bool fit_block_cycles = false;
  // Distributed run: the ranks that each hold a part of the state (system.size() is then the
  // local length, every rank passes the same options). ARKODE runs on SUNDIALS' parallel
  // vectors (global norms), and the system's return codes, max_stable_dt (min), root functions
  // (root_reduction) and option checks are reduced over the ranks, so every rank takes the
  // same steps (stepper.hpp). Default: serial, no MPI (the serial code path, unchanged).
  Communicator communicator;
  // ARKODE's error norm summed exactly (parallel/sundials_vector.hpp: independent of the order
  // of the entries and of how they are split over ranks), so that the run takes exactly the
  // steps of the same run on any number of ranks. Distributed runs always use it; false keeps
  // SUNDIALS' own (sequential) sum for serial runs, whose steps then agree with a distributed
  // run's until round-off first tips an accept/reject decision.
  bool reproducible_norms = false;
  // Distributed runs: how each root function g_k is combined over the ranks (each rank's
  // roots() sees only its own particles); missing entries mean ReduceOp::Min ("the first
  // particle to cross").
  std::vector<ReduceOp> root_reduction;
};

// One level of a multirate stepper (MRIStep: 0 slow, 1 fast; block steps: 0 the longest step).
struct LevelStats {
  long steps = 0;           // steps taken at this level
  long rhs_evals = 0;       // right-hand-side (subset) evaluations of this level's particles
  long particle_evals = 0;  // Σ over those evaluations of the particles evaluated
};

struct StepperStats {
  long steps = 0;                // accepted steps
  long attempts = 0;             // step attempts (accepted + rejected + retried)
  long rhs_evals = 0;            // evaluations of the explicit / full right-hand side
  long rhs_evals_implicit = 0;   // evaluations of the implicit part (IMEX only)
  long error_test_failures = 0;  // steps rejected by the temporal error test
  long nonlinear_failures = 0;   // nonlinear solver convergence failures (IMEX only)
  long rhs_recoveries = 0;       // restarts with a smaller step after a recoverable RHS failure
  long corrector_iterations = 0; // leapfrog: RHS evaluations repeated until the velocities agree
  long linear_solves = 0;        // custom diagonal linear solves (IMEX only)
  // Σ over RHS calls of the particles whose derivatives were computed (OdeSystem::num_particles()
  // per full RHS call, the active set per subset call): the unit of work of issue #17.
  long particle_evals = 0;
  std::vector<LevelStats> levels;  // multirate steppers only (empty for global steppers)
  Real last_dt = 0;              // size of the last step taken
  Real current_time = 0;         // time reached by the stepper
};

// One line for run summaries, e.g. "ERK ARKODE_DORMAND_PRINCE_7_4_5 adaptive rtol=1e-06 ...".
std::string describe(const StepperOptions& opts);
// One line: steps, attempts, rhs evals, error-test failures, ...
std::string format_stats(const StepperStats& stats);

}  // namespace sphark
