#pragma once
// One interface over every time stepper: ARKODE ERKStep (any explicit Butcher table),
// ARKODE ARKStep IMEX (stiff diagonal part implicit) and a kick-drift-kick leapfrog.
//
// Output times: every advance() lands exactly on t_out (ARKODE stop time), so the returned
// state is a genuine step of the method, never ARKODE's dense-output interpolant (whose order
// is below that of the high-order tables).
//
// Step-size bounds: max_dt when > 0. Adaptive ARKODE runs are also bounded by
// cfl_safety * system.max_stable_dt(t, y), evaluated at the start of every advance() call (a
// finite CFL limit is respected per output interval; StepperOptions::cap_by_stability = false
// lifts this bound). Fixed-step runs take fixed_dt (the last step of an interval is shortened
// to land on t_out). kStepsBelowFloor consecutive steps below StepperOptions::step_floor, or
// one step that leaves t unchanged (t + dt == t), end the run as Failed (the state before that
// step is the last good state).
//
// Interrupts: StepperOptions::interrupt is polled before every RHS evaluation (ARKODE: in the
// RHS callback, which then fails the step attempt; the leapfrog: also before every step and
// every root-location trial), so a stop signal ends advance() within one RHS evaluation.
//
// Recoverable RHS failures (return > 0): ARKODE 6.4.1 ERKStep/ARKStep turn them into
// ARK_UNREC_RHSFUNC_ERR for explicit stages, so the ERK/IMEX stepper restarts (xxxStepReset)
// from the last accepted step with a step 4x smaller than the failed one, and caps the step at
// half the failed one (fixed-step runs: uses that smaller fixed step) until the next
// advance(); up to 10 restarts without progress. The leapfrog halves dt and retries the step
// (up to 10 times); the next step starts again from fixed_dt / the CFL step.
//
// Roots: ARKODE's root finding; the leapfrog checks g after every step and locates the root
// on the leapfrog trajectory itself (Illinois iteration on the length of the last step), so
// the returned state is a genuine leapfrog state at the returned time.
//
// ark-imex on a system without a stiff part is an error (no silent fallback to ERK).
//
// Distributed runs (StepperOptions::communicator over MPI): each rank's stepper advances its
// local part of the state; every rank calls every Stepper function, in the same order. The
// system's return codes are made collective (the most severe code of any rank, with the
// failing ranks' messages in failure_reason()), max_stable_dt is the minimum over the ranks and
// each root function is reduced by StepperOptions::root_reduction, so all ranks take the same
// steps, fail together and find the same roots.
//
// Resizing (particles created, accreted or removed; migration to and from other ranks): between
// advance() calls, the system's size() may change; resize() then hands the stepper the new state
// at its current time. ARKODE keeps its step size and error history (ERKStepResize /
// ARKStepResize; before the first advance() its memory is created afresh), the leapfrog its
// time and step; the next advance() continues from there. Distributed: collective.
#include <memory>
#include <string>
#include <vector>

#include "sphark/integrate/ode_system.hpp"
#include "sphark/integrate/stepper_options.hpp"

namespace sphark {

// Stepped: step() took one step and t is still before t_out.
// Interrupted: StepperOptions::interrupt said so (a stop signal); y, t hold the last accepted
// step. A later advance() continues from there (the ARKODE steppers restart their memory at that
// step with the last step size as the first one; the leapfrog goes on as if never interrupted).
enum class AdvanceStatus { Reached, RootFound, Failed, Stepped, Interrupted };

class Stepper {  // one object per run; owns all SUNDIALS objects it uses (RAII)
 public:
  virtual ~Stepper() = default;
  // Advance to t_out. y (size system.size()) receives the state at t: t == t_out unless a root
  // was found (RootFound), the integration failed (Failed: y, t = last good state) or was
  // interrupted (Interrupted: y, t = last accepted step).
  // The stepper keeps its own state: the content of y on entry is ignored.
  // Throws std::invalid_argument if t_out is before the current time.
  virtual AdvanceStatus advance(Real t_out, Real* y, Real& t) = 0;
  // One step towards t_out (landing on it, never past it): Stepped with t < t_out, Reached at
  // t_out, or RootFound / Failed as advance(). Between two calls the caller may inspect y and
  // resize(). The step-size bounds of advance() are taken at every call. (Default: advance().)
  virtual AdvanceStatus step(Real t_out, Real* y, Real& t) { return advance(t_out, y, t); }
  virtual StepperStats stats() const = 0;
  // After Failed: flag name + message, time, and system.last_error().
  virtual std::string failure_reason() const = 0;
  // What a bit-exact restart at the current state needs beyond (t, y, last step): the
  // leapfrog's derivative for the next kick (FSAL: evaluated at the predictor, not at y) and its
  // time compensation; empty for the ARKODE steppers (they restart from (t, y) and initial_dt).
  // Pass it back as StepperOptions::resume_data.
  virtual std::vector<Real> resume_data() const { return {}; }
  // After RootFound: one entry per g_k, +1 / -1 if g_k crossed zero increasing / decreasing.
  virtual std::vector<int> roots_found() const = 0;

  // The new state after system.size() changed (see above), at the current time.
  struct Resized {
    const Real* y = nullptr;     // system.size() entries
    // Per-entry absolute tolerances of the new state: required when the run was configured with
    // one atol per entry, ignored otherwise.
    const Real* atol = nullptr;
    // The leapfrog's next-kick derivative in the new entry order (what carried_data() returned,
    // reordered like y); nullptr: evaluated afresh at y (then the step differs from an
    // uninterrupted run where the RHS depends on v). Ignored by the ARKODE steppers.
    const Real* carried = nullptr;
  };
  // Throws std::invalid_argument for a missing per-entry atol (on every rank of a distributed
  // run); std::logic_error if the stepper cannot resize.
  virtual void resize(const Resized& state);
  // Per-entry data aligned with the state that must move with its entries when they are
  // reordered or migrated (the leapfrog's next-kick derivative); empty for ARKODE.
  virtual std::vector<Real> carried_data() const { return {}; }
};

// Throws std::invalid_argument (one line naming the option and its value) for bad options:
// unknown method or IMEX table, atol of wrong size, non-positive rtol, ark-imex on a system
// without a stiff part, leapfrog without a position block or without any step-size limit.
std::unique_ptr<Stepper> make_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                      const Real* y0);

// Every explicit Butcher table of SUNDIALS 6.4.1, in ARKODE's enum order.
std::vector<std::string> erk_table_names();
// The explicit MRI coupling tables of SUNDIALS 6.4.1 (ARKODE_MIS_KW3, ARKODE_MRI_GARK_ERK33a,
// ARKODE_MRI_GARK_ERK45a): method "mri-<name>" (multirate, issue #17), and their orders.
std::vector<std::string> mri_table_names();
int mri_table_order(const std::string& name);  // 0 for an unknown name
// True if the table has an embedding (needed for adaptive steps; otherwise fixed_dt is required).
bool erk_table_has_embedding(const std::string& name);

}  // namespace sphark
