#include "arkode_stepper.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <limits>
#include <stdexcept>

#include "collective_checks.hpp"
#include "sphark/core/profile.hpp"
#include "number_text.hpp"

namespace sphark::detail {
namespace {

constexpr int kMaxRecoveries = 10;    // consecutive restarts after recoverable RHS failures
constexpr Real kRecoveryFactor = 0.25;  // step reduction per restart

// The system's max_stable_dt failed (NaN): the run stops instead of taking an uncapped step.
struct StableStepFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace

// *GetReturnFlagName returns a malloc'ed string owned by the caller.
std::string ArkodeStepper::flag_name(int flag) const {
  std::unique_ptr<char, decltype(&std::free)> name(api_.flag_name(flag), &std::free);
  return name ? std::string(name.get()) : "flag " + std::to_string(flag);
}

ArkodeStepper::ArkodeStepper(OdeSystem& system, const StepperOptions& opts, const ArkodeApi& api,
                             Real t0, const Real* y0)
    : system_(system),
      opts_(opts),
      api_(api),
      ctx_(make_context(opts.communicator)),
      y_last_(y0, y0 + system.size()),
      t_last_(t0),
      y_accepted_(y_last_),
      t_accepted_(t0) {
  const std::size_t n = system_.size();
  atol_ = opts_.atol.empty() ? std::vector<Real>{1e-9} : opts_.atol;
  per_entry_atol_ = atol_.size() == n && n > 1;
  if (opts_.communicator.distributed())  // one choice for all ranks (SVtolerances is collective)
    per_entry_atol_ = opts_.communicator.allreduce(std::int64_t(per_entry_atol_), ReduceOp::Max) != 0;
  if (per_entry_atol_ && n == 0) atol_.clear();  // a rank without entries (distributed runs only)
}

void ArkodeStepper::check(int flag, const char* call) const {
  if (flag < 0)
    throw std::runtime_error(std::string(api_.module) + call + " failed: " + flag_name(flag) +
                             (arkode_message_.empty() ? "" : " (" + arkode_message_ + ")"));
}

void ArkodeStepper::configure() {
  check(api_.set_user_data(mem_, this), "SetUserData");
  check(api_.set_err_handler(mem_, &error_cb, this), "SetErrHandlerFn");
  check(api_.set_postprocess_step(mem_, &step_done_cb), "SetPostprocessStepFn");
  set_tolerances();
  check(api_.set_max_num_steps(mem_, opts_.max_steps), "SetMaxNumSteps");
  if (opts_.fixed_dt > 0) check(api_.set_fixed_step(mem_, opts_.fixed_dt), "SetFixedStep");
  else if (opts_.initial_dt > 0) check(api_.set_init_step(mem_, opts_.initial_dt), "SetInitStep");
  if (system_.num_roots() > 0) {
    check(api_.root_init(mem_, system_.num_roots(), &roots_cb), "RootInit");
    check(api_.set_no_inactive_root_warn(mem_), "SetNoInactiveRootWarn");
  }
}

void ArkodeStepper::set_tolerances() {
  if (per_entry_atol_) {
    require_everywhere(opts_.communicator, atol_.size() == system_.size(),
                       "atol=" + std::to_string(atol_.size()) + " values: the distributed run uses one per state "
                       "entry, this rank has " + std::to_string(system_.size()));
    atol_view_ = view(atol_.size(), atol_.data());
    check(api_.sv_tolerances(mem_, opts_.rtol, atol_view_.get()), "SVtolerances");
  } else {
    check(api_.ss_tolerances(mem_, opts_.rtol, atol_.front()), "SStolerances");
  }
}

// Before each advance(): land exactly on t_out (stop time: the returned state is a genuine step,
// not ARKODE's dense-output interpolant, whose order is below that of high-order tables), and
// bound adaptive steps by max_dt and (cap_by_stability) cfl_safety * max_stable_dt at the
// current state.
void ArkodeStepper::bound_step(Real t_out) {
  realtype t_internal = 0;
  check(api_.get_current_time(mem_, &t_internal), "GetCurrentTime");
  if ((t_out - t_internal) * (t_out - t_last_) > 0) check(api_.set_stop_time(mem_, t_out), "SetStopTime");
  if (opts_.fixed_dt > 0) {
    if (fixed_step_reduced_) check(api_.set_fixed_step(mem_, opts_.fixed_dt), "SetFixedStep");
    fixed_step_reduced_ = false;
    return;
  }
  step_cap_ = opts_.max_dt > 0 ? opts_.max_dt : std::numeric_limits<Real>::infinity();
  if (opts_.cap_by_stability) {
    const Real stable = system_.max_stable_dt(t_last_, y_last_.data(), nullptr);
    if (!(stable > 0)) {  // NaN (or a non-positive step): the system could not tell a stable step
      std::string why = system_.last_error();
      throw StableStepFailure("max_stable_dt failed at t=" + at_time(t_last_) + " (returned " + at_time(stable) + ")" +
                              (why.empty() ? std::string() : ": " + why));
    }
    if (std::isfinite(stable)) step_cap_ = std::min(step_cap_, opts_.cfl_safety * stable);
  }
  check(api_.set_max_step(mem_, std::isfinite(step_cap_) ? step_cap_ : 0.0), "SetMaxStep");
}

// ARKODE 6.4.1 turns a recoverable failure of an explicit RHS evaluation into
// ARK_UNREC_RHSFUNC_ERR. Restart from the last accepted state with a step 4x smaller than the
// failed one; adaptive runs also cap the step at half the failed one until the next advance()
// (otherwise ARKODE regrows the step after the restart and fails again at once).
bool ArkodeStepper::recover(int& consecutive) {
  if (t_accepted_ != t_recovered_) consecutive = 0;  // progress since the last restart
  t_recovered_ = t_accepted_;
  if (++consecutive > kMaxRecoveries) return false;
  realtype h = 0;
  if (api_.get_current_step(mem_, &h) < 0 || !(std::abs(h) > 0)) return false;
  h = kRecoveryFactor * std::abs(h);
  if (h < opts_.min_dt) {
    below_min_dt_ = true;
    return false;
  }
  auto y = view(y_accepted_.size(), y_accepted_.data());
  if (api_.reset(mem_, t_accepted_, y.get()) < 0) return false;
  if (opts_.fixed_dt > 0) {
    if (api_.set_fixed_step(mem_, h) < 0) return false;
  } else {
    step_cap_ = std::min(step_cap_, 2 * h);
    if (api_.set_init_step(mem_, h) < 0 || api_.set_max_step(mem_, step_cap_) < 0) return false;
  }
  fixed_step_reduced_ = opts_.fixed_dt > 0;
  ++recoveries_;
  return true;
}

bool ArkodeStepper::interrupt_now() noexcept {
  if (interrupted_) return true;
  if (!opts_.interrupt) return false;
  try {
    interrupted_ = opts_.interrupt();
  } catch (...) {
    interrupted_ = true;  // a poll that cannot answer stops the run rather than letting it run on
  }
  return interrupted_;
}

// The next advance() after an interrupt: ARKODE restarts at the last accepted step, with that
// step's size as its first (the failed step attempt left its memory mid-step).
void ArkodeStepper::restart_after_interrupt() {
  realtype h_initial = 0, h_last = 0, h_current = 0, t_current = 0;
  long steps = 0;
  api_.get_step_stats(mem_, &steps, &h_initial, &h_last, &h_current, &t_current);
  auto y = view(y_last_.size(), y_last_.data());
  check(api_.reset(mem_, t_last_, y.get()), "Reset");
  if (!(opts_.fixed_dt > 0) && h_last > 0) check(api_.set_init_step(mem_, h_last), "SetInitStep");
  restart_pending_ = false;
}

// Failed or Interrupted: the state after the last accepted step is the one returned.
AdvanceStatus ArkodeStepper::end_at_last_accepted(Real* y, Real& t, AdvanceStatus status) {
  y_last_ = y_accepted_;
  t_last_ = t_accepted_;
  std::copy(y_last_.begin(), y_last_.end(), y);
  t = t_last_;
  return status;
}

std::string ArkodeStepper::failure_text(int flag, Real t, int consecutive) const {
  if (!floor_failure_.empty()) return floor_failure_;
  std::string why = flag_name(flag) + " (" + std::to_string(flag) + ") at t=" + at_time(t) + ": " + arkode_message_;
  if (!callback_error_.empty()) why += "; " + callback_error_;
  if (below_min_dt_) why += "; the reduced step would fall below min_dt=" + at_time(opts_.min_dt);
  if (consecutive > kMaxRecoveries) why += "; gave up after " + std::to_string(kMaxRecoveries) + " step reductions";
  return why;
}

AdvanceStatus ArkodeStepper::evolve_to(Real t_out, Real* y, Real& t, int itask) {
  ScopedPhase timer(Phase::Advance);
  const std::size_t n = system_.size();
  roots_.clear();
  if (t_out < t_last_) throw std::invalid_argument("t_out=" + at_time(t_out) + ": before the current time " + at_time(t_last_));
  if (failed_ || t_out == t_last_) {
    std::copy(y_last_.begin(), y_last_.end(), y);
    t = t_last_;
    return failed_ ? AdvanceStatus::Failed : AdvanceStatus::Reached;
  }
  interrupted_ = false;
  if (restart_pending_) restart_after_interrupt();
  t_out_ = t_out;
  auto yout = view(n, y);
  try {
    bound_step(t_out);
  } catch (const StableStepFailure& e) {
    failed_ = true;
    failure_ = e.what();
    std::copy(y_last_.begin(), y_last_.end(), y);
    t = t_last_;
    return AdvanceStatus::Failed;
  }
  for (int consecutive = 0;;) {
    last_code_ = 0;
    callback_error_.clear();
    arkode_message_.clear();
    evolved_ = true;
    const int flag = api_.evolve(mem_, t_out, yout.get(), &t, itask);
    if (flag >= 0) {
      std::copy(y, y + n, y_last_.begin());
      t_last_ = t;
      if (flag != ARK_ROOT_RETURN) return t < t_out ? AdvanceStatus::Stepped : AdvanceStatus::Reached;
      roots_.assign(static_cast<std::size_t>(system_.num_roots()), 0);
      check(api_.get_root_info(mem_, roots_.data()), "GetRootInfo");
      return AdvanceStatus::RootFound;
    }
    if (interrupted_) {  // the RHS callback refused to evaluate: a stop request
      restart_pending_ = true;
      return end_at_last_accepted(y, t, AdvanceStatus::Interrupted);
    }
    const bool rhs_flag = flag == ARK_UNREC_RHSFUNC_ERR || flag == ARK_REPTD_RHSFUNC_ERR ||
                          flag == ARK_FIRST_RHSFUNC_ERR;
    if (rhs_flag && last_code_ > 0 && recover(consecutive)) continue;
    failed_ = true;
    failure_ = failure_text(flag, t, consecutive);
    return end_at_last_accepted(y, t, AdvanceStatus::Failed);
  }
}

// xxxStepResize at the current time with the step size kept (hscale 1): ARKODE keeps its step
// and error history and re-clones its vectors from the new state. The re-cloned Vabstol holds
// no values, so adaptive runs set the tolerances again (fixed-step runs keep ARKODE's own
// error weights, which SStolerances would replace).
void ArkodeStepper::resize(const Resized& state) {
  const std::size_t n = system_.size();
  const bool adaptive = !(opts_.fixed_dt > 0);
  require_everywhere(opts_.communicator, !(adaptive && per_entry_atol_ && n > 0 && state.atol == nullptr),
                     "resize: the run uses one atol per state entry; give those of the new state");
  require_everywhere(opts_.communicator, !(n > 0 && state.y == nullptr), "resize: no state");
  y_last_.assign(state.y, state.y + n);
  y_accepted_ = y_last_;
  t_accepted_ = t_last_;
  if (adaptive && per_entry_atol_) atol_.assign(state.atol, state.atol + n);
  if (!evolved_) {  // ARKODE 6.4.1 allocates its stage vectors at the first evolve: start afresh
    create(t_last_);
    return;
  }
  auto y = view(n, y_last_.data());
  check(api_.resize(mem_, y.get(), 1.0, t_last_, nullptr, nullptr), "Resize");
  if (adaptive) set_tolerances();
  after_resize();
}

StepperStats ArkodeStepper::stats() const {
  StepperStats s;
  realtype h_initial = 0, h_current = 0, t_current = 0;
  api_.get_step_stats(mem_, &s.steps, &h_initial, &s.last_dt, &h_current, &t_current);
  api_.get_num_step_attempts(mem_, &s.attempts);
  api_.get_num_err_test_fails(mem_, &s.error_test_failures);
  s.rhs_recoveries = recoveries_;
  s.current_time = t_last_;
  add_method_stats(s);
  return s;
}

void ArkodeStepper::record(const char* what, Real t, int code) noexcept {
  last_code_ = code;
  try {
    callback_error_ = std::string(what) + " returned " + std::to_string(code) + " at t=" +
                      at_time(t) + " (" + (code > 0 ? "recoverable" : "fatal") + ")";
    const std::string reason = system_.last_error();
    if (!reason.empty()) callback_error_ += ": " + reason;
  } catch (const std::exception& e) {
    record_exception(what, t, e.what());
  } catch (...) {
    record_exception(what, t, "unknown exception");
  }
}

void ArkodeStepper::record_exception(const char* what, Real t, const char* message) noexcept {
  last_code_ = -1;
  try {
    callback_error_ = std::string(what) + " threw an exception at t=" + at_time(t) + ": " + message;
  } catch (...) {
    callback_error_.clear();  // out of memory: the flag name still reports the failure
  }
}

int ArkodeStepper::roots_cb(realtype t, N_Vector y, realtype* g, void* self) {
  auto* s = static_cast<ArkodeStepper*>(self);
  return s->guarded("roots", t, [&] { return s->system_.roots(t, N_VGetArrayPointer(y), g); });
}

// After every accepted step: a step that does not advance t, or the kStepsBelowFloor-th in a row
// below the step floor (a step landing on t_out does not count), ends the run with the state before it (returning non-zero
// makes ARKODE stop with ARK_POSTPROCESS_STEP_FAIL before it counts the step).
int ArkodeStepper::step_done_cb(realtype t, N_Vector y, void* self) {
  auto* s = static_cast<ArkodeStepper*>(self);
  const Real dt = t - s->t_accepted_;
  if (t != s->t_out_) s->steps_below_floor_ = s->opts_.step_floor > 0 && dt < s->opts_.step_floor ? s->steps_below_floor_ + 1 : 0;
  const bool below_floor = s->steps_below_floor_ >= kStepsBelowFloor;
  if (!(t > s->t_accepted_) || below_floor) {
    try {
      s->floor_failure_ = "a step of dt=" + at_time(dt) + " at t=" + at_time(s->t_accepted_) +
                          (below_floor ? ": " + std::to_string(kStepsBelowFloor) + " steps in a row below the step floor " +
                                             at_time(s->opts_.step_floor)
                                       : " does not advance t (t + dt == t)");
    } catch (...) {
    }
    return 1;
  }
  const Real* data = N_VGetArrayPointer(y);
  std::copy(data, data + s->y_accepted_.size(), s->y_accepted_.begin());
  s->t_accepted_ = t;
  return 0;
}

void ArkodeStepper::error_cb(int code, const char* module, const char* function, char* msg,
                             void* self) {
  if (code == ARK_WARNING) return;
  try {
    static_cast<ArkodeStepper*>(self)->arkode_message_ =
        std::string(module) + "::" + function + ": " + msg;
  } catch (...) {
  }
}

}  // namespace sphark::detail
