// ARKODE MRIStep (multirate infinitesimal GARK / MIS methods; Sandu 2019 SINUM 57, Chinomona &
// Reynolds 2021 SISC 43; Knoth & Wolke 1998 for MIS) over a slow/fast partition of the particles
// (issue #17): f = f_slow + f_fast, f_fast the derivatives of the fast particles, f_slow those of
// the others, each computed against every neighbour (OdeSystem::rhs_subset). The slow method is
// the coupling table (fixed step StepperOptions::fixed_dt: MRIStep of SUNDIALS 6.4.1 has no slow
// step adaptivity); the fast integrator an explicit ARKStep (ERKStep has no MRIStep inner-stepper
// constructor in 6.4.1; ARKStep with an explicit table only is the same ERK method) with the
// fixed step fixed_dt / mri_ratio. The partition (LevelPartition, levels 0 slow / >= 1 fast) is
// redone after every slow step, in MRIStep's step post-processing callback: it runs before
// MRIStep evaluates f_slow at the new step (the first stage of the next step), so the next step
// is exactly the first step of a fresh MRIStep at that state with the new partition.
// Every SUNDIALS object is owned by an RAII holder; no exception crosses a C callback.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>

#include "sphark/core/profile.hpp"
#include "sphark/integrate/callback_errors.hpp"
#include "mri_split.hpp"
#include "steppers.hpp"
#include "sundials_handles.hpp"
#include "number_text.hpp"

namespace sphark {

// The explicit coupling tables of arkode/arkode_mristep.h (6.4.1) and their orders (the
// ARKODE_MRITableID comments / SUNDIALS docs, "MRIStep coupling tables").
std::vector<std::string> mri_table_names() {
  return {"ARKODE_MIS_KW3", "ARKODE_MRI_GARK_ERK33a", "ARKODE_MRI_GARK_ERK45a"};
}

int mri_table_order(const std::string& name) {
  if (name == "ARKODE_MIS_KW3" || name == "ARKODE_MRI_GARK_ERK33a") return 3;
  if (name == "ARKODE_MRI_GARK_ERK45a") return 4;
  return 0;
}

namespace detail {
namespace {

enum Level { kSlow = 0, kFast = 1 };

class MriStepper final : public Stepper {
 public:
  MriStepper(OdeSystem& system, const StepperOptions& opts, Real t0, const Real* y0);
  AdvanceStatus advance(Real t_out, Real* y, Real& t) override;
  AdvanceStatus step(Real t_out, Real* y, Real& t) override;
  StepperStats stats() const override;
  std::string failure_reason() const override { return failure_; }
  std::vector<int> roots_found() const override { return {}; }
  // The partition (each particle's level), so that a restart at (t, y) bins exactly as this
  // run would have: with it, the restart takes this run's steps bit for bit.
  // With it the latest derivatives handed to particle_stable_dt, when there are.
  std::vector<Real> resume_data() const override {
    std::vector<Real> r(split_.levels().begin(), split_.levels().end());
    if (approx_valid_[kSlow] && approx_valid_[kFast]) r.insert(r.end(), approx_f_.begin(), approx_f_.end());
    return r;
  }
  // Between slow steps: MRIStep and its fast integrator start afresh at (t, new y) (their step
  // sizes are fixed; nothing else carries over), the partition is binned afresh.
  void resize(const Resized& state) override;

 private:
  void create(Real t0);
  void check(int flag, const char* call) const;
  void repartition(Real t, const Real* y);
  int evaluate(Level level, realtype t, N_Vector y, N_Vector ydot) noexcept;
  AdvanceStatus end_at_last_step(Real* y, Real& t, AdvanceStatus status);
  std::string failure_text(int flag) const;
  static int slow_cb(realtype t, N_Vector y, N_Vector ydot, void* self);
  static int fast_cb(realtype t, N_Vector y, N_Vector ydot, void* self);
  static int step_done_cb(realtype t, N_Vector y, void* self);
  static void error_cb(int code, const char* module, const char* function, char* msg, void* self);

  OdeSystem& system_;
  const StepperOptions opts_;
  ContextPtr ctx_;
  std::vector<Real> y_;  // state after the last accepted slow step
  Real t_;
  MriSplit split_;
  Real h_slow_set_ = 0, h_fast_set_ = 0;  // the fixed steps MRIStep and ARKStep were given
  std::vector<std::size_t> sets_[2];  // slow, fast particles (ascending)
  std::vector<Real> stable_dt_;
  // The latest f_slow and f_fast values of each set's entries: the derivative handed to
  // particle_stable_dt (its "stepper's approximation of f"; valid once both sets have been
  // evaluated since the last repartition).
  std::vector<Real> approx_f_;
  std::vector<std::size_t> set_entries_[2];
  bool approx_valid_[2] = {false, false};
  long base_slow_steps_ = 0, base_fast_steps_ = 0;  // of the memories replaced by resize()
  LevelStats level_stats_[2];
  long repartitions_ = 0;  // partitions that changed a set
  bool sets_valid_ = false;  // sets_ follow partition_ (false until the first repartition)
  ArkMemPtr fast_mem_;     // destroyed last: the inner stepper and MRIStep refer to it
  InnerStepperPtr inner_;
  MriMemPtr mem_;
  std::string failure_, callback_error_, arkode_message_;
  bool failed_ = false, interrupted_ = false, restart_pending_ = false;
};

MriStepper::MriStepper(OdeSystem& system, const StepperOptions& opts, Real t0, const Real* y0)
    : system_(system),
      opts_(opts),
      ctx_(make_context()),
      y_(y0, y0 + system.size()),
      t_(t0),
      split_(opts) {
  const std::vector<Real>& r = opts.resume_data;
  const std::size_t np = system.num_particles();
  if (!r.empty()) {  // a restart: the partition (and derivatives) of the run being continued
    if (r.size() != np && r.size() != np + y_.size())
      throw std::invalid_argument("resume_data: " + std::to_string(r.size()) + " values, expected " +
                                  std::to_string(np) + " or " + std::to_string(np + y_.size()));
    split_.set_levels(std::vector<int>(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(np)));
    if (r.size() > np) {
      approx_f_.assign(r.begin() + static_cast<std::ptrdiff_t>(np), r.end());
      approx_valid_[kSlow] = approx_valid_[kFast] = true;
    }
  }
  repartition(t0, y0);
  create(t0);
}

void MriStepper::check(int flag, const char* call) const {
  if (flag < 0)
    throw std::runtime_error(std::string(call) + " failed (flag " + std::to_string(flag) + ")" +
                             (arkode_message_.empty() ? "" : ": " + arkode_message_));
}

// The fast ARKStep (explicit table only, fixed step), its inner-stepper wrapper, the MRIStep.
void MriStepper::create(Real t0) {
  auto y0 = make_view(y_.size(), y_.data(), ctx_.get());  // copied by the Create calls
  fast_mem_.reset(ARKStepCreate(&fast_cb, nullptr, t0, y0.get(), ctx_.get()));
  if (!fast_mem_) throw std::runtime_error("ARKStepCreate (MRIStep fast integrator) failed");
  void* fast = fast_mem_.get();
  check(ARKStepSetUserData(fast, this), "ARKStepSetUserData");
  check(ARKStepSetErrHandlerFn(fast, &error_cb, this), "ARKStepSetErrHandlerFn");
  if (ARKStepSetTableName(fast, "ARKODE_DIRK_NONE", opts_.mri_fast_table.c_str()) < 0)
    throw std::invalid_argument("mri_fast_table=" + opts_.mri_fast_table + ": ARKStepSetTableName rejected it");
  check(ARKStepSetFixedStep(fast, split_.h_fast()), "ARKStepSetFixedStep");
  // Lagrange: the default Hermite interpolant costs one more f_fast evaluation per fast step.
  check(ARKStepSetInterpolantType(fast, ARK_INTERP_LAGRANGE), "ARKStepSetInterpolantType");
  check(ARKStepSetMaxNumSteps(fast, opts_.max_steps), "ARKStepSetMaxNumSteps");
  MRIStepInnerStepper inner = nullptr;
  check(ARKStepCreateMRIStepInnerStepper(fast, &inner), "ARKStepCreateMRIStepInnerStepper");
  inner_.reset(inner);
  mem_.reset(MRIStepCreate(&slow_cb, nullptr, t0, y0.get(), inner, ctx_.get()));
  if (!mem_) throw std::runtime_error("MRIStepCreate failed");
  void* mem = mem_.get();
  check(MRIStepSetUserData(mem, this), "MRIStepSetUserData");  // before the post-processing fn
  check(MRIStepSetErrHandlerFn(mem, &error_cb, this), "MRIStepSetErrHandlerFn");
  check(MRIStepSetPostprocessStepFn(mem, &step_done_cb), "MRIStepSetPostprocessStepFn");
  MRIStepCoupling table = MRIStepCoupling_LoadTableByName(opts_.method.substr(4).c_str());
  if (table == nullptr) throw std::invalid_argument("method=" + opts_.method + ": no such MRI coupling table");
  const int flag = MRIStepSetCoupling(mem, table);
  MRIStepCoupling_Free(table);  // copied by MRIStepSetCoupling
  check(flag, "MRIStepSetCoupling");
  check(MRIStepSetFixedStep(mem, split_.h_slow()), "MRIStepSetFixedStep");
  h_slow_set_ = split_.h_slow(), h_fast_set_ = split_.h_fast();
  check(MRIStepSetMaxNumSteps(mem, opts_.max_steps), "MRIStepSetMaxNumSteps");
}

// The split at (t, y) from the particles' stable steps x cfl_safety (mri_split.hpp).
void MriStepper::repartition(Real t, const Real* y) {
  stable_dt_.assign(system_.num_particles(), 0);
  const bool approx = approx_valid_[kSlow] && approx_valid_[kFast] && approx_f_.size() == y_.size();
  if (const int code = system_.particle_stable_dt(t, y, approx ? approx_f_.data() : nullptr, stable_dt_.data()); code != 0)
    throw std::runtime_error("particle_stable_dt failed (code " + std::to_string(code) + ") at t=" + at_time(t) +
                             ": " + system_.last_error());
  for (Real& dt : stable_dt_) dt *= opts_.cfl_safety;
  if (!split_.update(stable_dt_, t) && sets_valid_) return;
  sets_valid_ = true;
  sets_[kSlow] = split_.slow();
  sets_[kFast] = split_.fast();
  ++repartitions_;
  const std::vector<std::size_t> owner = system_.entry_particles();
  set_entries_[kSlow].clear(), set_entries_[kFast].clear();
  for (std::size_t k = 0; k < owner.size(); ++k) set_entries_[split_.is_fast(owner[k])].push_back(k);
  approx_f_.resize(y_.size());
  approx_valid_[kSlow] = sets_[kSlow].empty(), approx_valid_[kFast] = sets_[kFast].empty();
}

// One level's derivatives (the other level's entries zero); an empty set costs no evaluation.
int MriStepper::evaluate(Level level, realtype t, N_Vector y, N_Vector ydot) noexcept {
  try {
    if (opts_.interrupt && !interrupted_) interrupted_ = opts_.interrupt();
  } catch (...) {
    interrupted_ = true;
  }
  if (interrupted_) return -1;
  const std::vector<std::size_t>& set = sets_[level];
  if (set.empty()) {
    N_VConst(0.0, ydot);
    return 0;
  }
  ++level_stats_[level].rhs_evals;
  level_stats_[level].particle_evals += static_cast<long>(set.size());
  try {
    const int code = system_.rhs_subset(t, N_VGetArrayPointer(y), set, N_VGetArrayPointer(ydot));
    if (code == 0) {  // the latest values of this set's derivatives
      const Real* f = N_VGetArrayPointer(ydot);
      for (std::size_t k : set_entries_[level]) approx_f_[k] = f[k];
      approx_valid_[level] = true;
    }
    if (code != 0)
      callback_error_ = std::string(level == kSlow ? "slow" : "fast") + " rhs returned " + std::to_string(code) +
                        " at t=" + at_time(t) + ": " + system_.last_error();
    return code;
  } catch (...) {
    callback_error_ = current_exception_message(level == kSlow ? "slow rhs" : "fast rhs");
  }
  return -1;
}

int MriStepper::slow_cb(realtype t, N_Vector y, N_Vector ydot, void* self) {
  return static_cast<MriStepper*>(self)->evaluate(kSlow, t, y, ydot);
}

int MriStepper::fast_cb(realtype t, N_Vector y, N_Vector ydot, void* self) {
  return static_cast<MriStepper*>(self)->evaluate(kFast, t, y, ydot);
}

// After every accepted slow step, before MRIStep evaluates f_slow there: the new partition.
int MriStepper::step_done_cb(realtype t, N_Vector y, void* self) {
  auto* s = static_cast<MriStepper*>(self);
  try {
    s->repartition(t, N_VGetArrayPointer(y));
    return 0;
  } catch (...) {
    s->callback_error_ = current_exception_message("repartition");
  }
  return -1;
}

void MriStepper::error_cb(int, const char* module, const char* function, char* msg, void* self) {
  try {
    static_cast<MriStepper*>(self)->arkode_message_ = std::string(module) + "::" + function + ": " + msg;
  } catch (...) {
  }
}

std::string MriStepper::failure_text(int flag) const {
  std::unique_ptr<char, decltype(&std::free)> name(MRIStepGetReturnFlagName(flag), &std::free);
  std::string why = std::string(name ? name.get() : "?") + " (" + std::to_string(flag) + ") at t=" + at_time(t_);
  if (!arkode_message_.empty()) why += ": " + arkode_message_;
  if (!callback_error_.empty()) why += "; " + callback_error_;
  return why;
}

void MriStepper::resize(const Resized& state) {
  if (state.y == nullptr) throw std::invalid_argument("resize: no state");
  long slow = 0, fast = 0;
  MRIStepGetNumSteps(mem_.get(), &slow);
  ARKStepGetNumSteps(fast_mem_.get(), &fast);
  base_slow_steps_ += slow, base_fast_steps_ += fast;
  mem_.reset();  // in this order: MRIStep refers to the inner stepper, which refers to ARKStep
  inner_.reset();
  fast_mem_.reset();
  y_.assign(state.y, state.y + system_.size());
  sets_valid_ = false;
  approx_valid_[kSlow] = approx_valid_[kFast] = false;
  restart_pending_ = false;
  repartition(t_, y_.data());  // a new particle count bins afresh
  create(t_);
}

AdvanceStatus MriStepper::end_at_last_step(Real* y, Real& t, AdvanceStatus status) {
  std::copy(y_.begin(), y_.end(), y);
  t = t_;
  return status;
}

// One slow step towards t_out (MRIStep lands on its stop time: the last step is shortened).
AdvanceStatus MriStepper::step(Real t_out, Real* y, Real& t) {
  ScopedPhase timer(Phase::Advance);
  if (t_out < t_) throw std::invalid_argument("t_out=" + at_time(t_out) + ": before the current time " + at_time(t_));
  if (failed_ || t_out == t_) return end_at_last_step(y, t, failed_ ? AdvanceStatus::Failed : AdvanceStatus::Reached);
  if (restart_pending_) {  // after an interrupt: MRIStep restarts at the last accepted step
    auto y_view = make_view(y_.size(), y_.data(), ctx_.get());
    check(MRIStepReset(mem_.get(), t_, y_view.get()), "MRIStepReset");
    restart_pending_ = false;
  }
  interrupted_ = false;
  callback_error_.clear();
  if (split_.h_slow() != h_slow_set_ || split_.h_fast() != h_fast_set_) {  // adaptive: new steps
    // ARKODE takes h = hin at every fixed step: the next step is that of a fresh MRIStep.
    check(MRIStepSetFixedStep(mem_.get(), split_.h_slow()), "MRIStepSetFixedStep");
    check(ARKStepSetFixedStep(fast_mem_.get(), split_.h_fast()), "ARKStepSetFixedStep");
    h_slow_set_ = split_.h_slow(), h_fast_set_ = split_.h_fast();
  }
  check(MRIStepSetStopTime(mem_.get(), t_out), "MRIStepSetStopTime");
  auto yout = make_view(y_.size(), y, ctx_.get());
  realtype t_reached = t_;
  const int flag = MRIStepEvolve(mem_.get(), t_out, yout.get(), &t_reached, ARK_ONE_STEP);
  if (flag < 0) {
    if (interrupted_) {
      restart_pending_ = true;
      return end_at_last_step(y, t, AdvanceStatus::Interrupted);
    }
    failed_ = true;
    failure_ = failure_text(flag);
    return end_at_last_step(y, t, AdvanceStatus::Failed);
  }
  std::copy(y, y + y_.size(), y_.begin());
  t = t_ = t_reached;
  return t_ < t_out ? AdvanceStatus::Stepped : AdvanceStatus::Reached;
}

AdvanceStatus MriStepper::advance(Real t_out, Real* y, Real& t) { return detail::advance_by_steps(*this, t_out, y, t); }

// Level 0 slow (steps, f_slow evaluations), level 1 fast (inner steps, f_fast evaluations);
// rhs_evals counts both (the subset calls); particle_evals is filled in by the guard.
StepperStats MriStepper::stats() const {
  StepperStats s;
  long slow_steps = 0, fast_steps = 0;
  MRIStepGetNumSteps(mem_.get(), &slow_steps);
  ARKStepGetNumSteps(fast_mem_.get(), &fast_steps);
  slow_steps += base_slow_steps_, fast_steps += base_fast_steps_;
  s.steps = s.attempts = slow_steps;
  s.levels = {level_stats_[kSlow], level_stats_[kFast]};
  s.levels[kSlow].steps = slow_steps;
  s.levels[kFast].steps = fast_steps;
  s.rhs_evals = level_stats_[kSlow].rhs_evals + level_stats_[kFast].rhs_evals;
  s.particle_evals = level_stats_[kSlow].particle_evals + level_stats_[kFast].particle_evals;
  MRIStepGetLastStep(mem_.get(), &s.last_dt);
  s.current_time = t_;
  return s;
}

}  // namespace

std::unique_ptr<Stepper> make_mri_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                          const Real* y0) {
  return std::make_unique<MriStepper>(system, opts, t0, y0);
}

}  // namespace detail
}  // namespace sphark
