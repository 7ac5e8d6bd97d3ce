// ARKODE MRIStep (multirate infinitesimal GARK / MIS methods; Sandu 2019 SINUM 57, Chinomona &
// Reynolds 2021 SISC 43; Knoth & Wolke 1998 for MIS) over a partition of the particles into K
// levels (issue #17; K = StepperOptions::mri_levels, 2 by default): f = f_0 + ... + f_{K-1}, f_k
// the derivatives of level k's particles, each computed against every neighbour
// (OdeSystem::rhs_subset). Level 0 is the slow method (the coupling table, fixed step: MRIStep of
// SUNDIALS 6.4.1 has no slow step adaptivity); the fastest level an explicit ARKStep (ERKStep
// has no MRIStep inner-stepper constructor in 6.4.1; ARKStep with an explicit table only is the
// same ERK method). More than two levels nest (Sandu 2019 §7, "telescopic" MRI): level k's
// MRIStep (0 < k < K-1), with the same coupling table and fixed step, is the inner stepper of
// level k-1's through a custom MRIStepInnerStepper (evolve: MRIStepEvolve to the stop time; reset:
// MRIStepReset; full RHS: f_k + ... + f_{K-1} in one subset evaluation), and its slow function
// is f_k plus the forcing polynomial of level k-1 (MRIStepInnerStepper_AddForcing), as ARKStep
// adds it to its own RHS when it is the inner stepper. The partition (MriSplit) is redone after
// every slow step, in the outer MRIStep's step post-processing callback: it runs before MRIStep
// evaluates f_0 at the new step (the first stage of the next step), so the next step is exactly
// the first step of a fresh MRIStep at that state with the new partition.
// Every SUNDIALS object is owned by an RAII holder; no exception crosses a C callback.
// This file: the partition, the levels' evaluations, the steps and statistics; the chain of
// integrators and its C callbacks are in mri_chain.cpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>

#include "sphark/core/profile.hpp"
#include "sphark/integrate/callback_errors.hpp"
#include "mri_stepper.hpp"
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

MriStepper::MriStepper(OdeSystem& system, const StepperOptions& opts, Real t0, const Real* y0)
    : system_(system),
      opts_(opts),
      ctx_(make_context()),
      y_(y0, y0 + system.size()),
      t_(t0),
      split_(opts) {
  const auto K = static_cast<std::size_t>(levels());
  h_set_.assign(K, 0);
  sets_.resize(K), set_entries_.resize(K), approx_valid_.assign(K, false);
  base_steps_.assign(K, 0), level_stats_.resize(K), forcing_on_.assign(K, 0);
  for (int k = 0; k < levels(); ++k) contexts_.push_back(std::make_unique<LevelContext>(LevelContext{this, k}));
  const std::vector<Real>& r = opts.resume_data;
  const std::size_t np = system.num_particles();
  if (!r.empty()) {  // a restart: the partition (and derivatives) of the run being continued
    if (r.size() != np && r.size() != np + y_.size())
      throw std::invalid_argument("resume_data: " + std::to_string(r.size()) + " values, expected " +
                                  std::to_string(np) + " or " + std::to_string(np + y_.size()));
    split_.set_levels(std::vector<int>(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(np)));
    if (r.size() > np) {
      approx_f_.assign(r.begin() + static_cast<std::ptrdiff_t>(np), r.end());
      approx_valid_.assign(K, true);
    }
  }
  repartition(t0, y0);
  depth_ = split_.depth();
  create(t0);
}

void MriStepper::check(int flag, const char* call) const {
  if (flag < 0)
    throw std::runtime_error(std::string(call) + " failed (flag " + std::to_string(flag) + ")" +
                             (arkode_message_.empty() ? "" : ": " + arkode_message_));
}

// The split at (t, y) from the particles' stable steps x cfl_safety (mri_split.hpp).
void MriStepper::repartition(Real t, const Real* y) {
  stable_dt_.assign(system_.num_particles(), 0);
  const bool approx = all_approx_valid() && approx_f_.size() == y_.size();
  if (const int code = system_.particle_stable_dt(t, y, approx ? approx_f_.data() : nullptr, stable_dt_.data()); code != 0)
    throw std::runtime_error("particle_stable_dt failed (code " + std::to_string(code) + ") at t=" + at_time(t) +
                             ": " + system_.last_error());
  for (Real& dt : stable_dt_) dt *= opts_.cfl_safety;
  if (!split_.update(stable_dt_, t) && sets_valid_) return;
  sets_valid_ = true;
  const auto K = static_cast<std::size_t>(levels());
  for (std::size_t k = 0; k < K; ++k) sets_[k] = split_.set(static_cast<int>(k)), set_entries_[k].clear();
  ++repartitions_;
  const std::vector<std::size_t> owner = system_.entry_particles();
  for (std::size_t k = 0; k < owner.size(); ++k)
    set_entries_[static_cast<std::size_t>(split_.level_of(owner[k]))].push_back(k);
  approx_f_.resize(y_.size());
  for (std::size_t k = 0; k < K; ++k) approx_valid_[k] = sets_[k].empty();
}

// The derivatives of `set` (counted as level `level`'s; the other entries zero); an empty set
// costs no evaluation.
int MriStepper::evaluate_set(int level, const std::vector<std::size_t>& set, realtype t, N_Vector y, N_Vector ydot) {
  if (set.empty()) {
    N_VConst(0.0, ydot);
    return 0;
  }
  LevelStats& stats = level_stats_[static_cast<std::size_t>(level)];
  ++stats.rhs_evals;
  stats.particle_evals += static_cast<long>(set.size());
  const int code = system_.rhs_subset(t, N_VGetArrayPointer(y), set, N_VGetArrayPointer(ydot));
  if (code != 0)
    callback_error_ = "level " + std::to_string(level) + " rhs returned " + std::to_string(code) + " at t=" +
                      at_time(t) + ": " + system_.last_error();
  return code;
}

// Level `level`'s derivatives, plus the forcing of the level above inside its wrapper's evolve.
int MriStepper::evaluate(int level, realtype t, N_Vector y, N_Vector ydot) noexcept {
  try {
    if (opts_.interrupt && !interrupted_) interrupted_ = opts_.interrupt();
  } catch (...) {
    interrupted_ = true;
  }
  if (interrupted_) return -1;
  const auto k = static_cast<std::size_t>(level);
  try {
    const int code = evaluate_set(level, sets_[k], t, y, ydot);
    if (code != 0) return code;
    const Real* f = N_VGetArrayPointer(ydot);  // the latest values of this set's derivatives
    for (std::size_t e : set_entries_[k]) approx_f_[e] = f[e];
    approx_valid_[k] = true;
    if (forcing_on_[k]) check(MRIStepInnerStepper_AddForcing(inner_[k].get(), t, ydot), "MRIStepInnerStepper_AddForcing");
    return 0;
  } catch (...) {
    callback_error_ = current_exception_message("level " + std::to_string(level) + " rhs");
  }
  return -1;
}

// f_level + ... + f_{K-1} in one subset evaluation (a wrapper's full RHS, without forcing).
int MriStepper::evaluate_from(int level, realtype t, N_Vector y, N_Vector ydot) noexcept {
  try {
    std::vector<std::size_t> set;
    for (int k = level; k < levels(); ++k) set.insert(set.end(), sets_[static_cast<std::size_t>(k)].begin(), sets_[static_cast<std::size_t>(k)].end());
    std::sort(set.begin(), set.end());
    return evaluate_set(level, set, t, y, ydot);
  } catch (...) {
    callback_error_ = current_exception_message("level " + std::to_string(level) + " full rhs");
  }
  return -1;
}

// After every accepted slow step, before MRIStep evaluates f_0 there: the new partition.
int MriStepper::step_done_cb(realtype t, N_Vector y, void* context) {
  MriStepper* s = static_cast<LevelContext*>(context)->stepper;
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
  y_.assign(state.y, state.y + system_.size());
  sets_valid_ = false;
  approx_valid_.assign(approx_valid_.size(), false);
  restart_pending_ = false;
  repartition(t_, y_.data());  // a new particle count bins afresh
  rebuild();
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
  // The deepest occupied level moved: the integrators afresh at (t_, y_), which is exactly the
  // next step of the old ones (each slow step starts as a fresh MRIStep's first; its slow RHS at
  // t_ is evaluated once more).
  if (split_.depth() != depth_) rebuild();
  set_steps();
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

// Level 0 slow (steps, f_0 evaluations), level k its MRIStep's or (the last) the ARKStep's
// steps and f_k evaluations (a wrapper's full RHS counts as its level's); rhs_evals counts all
// the subset calls; particle_evals is filled in by the guard.
StepperStats MriStepper::stats() const {
  StepperStats s;
  s.levels = level_stats_;
  for (int k = 0; k < levels(); ++k) {
    const auto ku = static_cast<std::size_t>(k);
    s.levels[ku].steps = steps_of(k) + base_steps_[ku];
    s.rhs_evals += level_stats_[ku].rhs_evals;
    s.particle_evals += level_stats_[ku].particle_evals;
  }
  s.steps = s.attempts = s.levels.front().steps;
  MRIStepGetLastStep(mem_.get(), &s.last_dt);
  s.current_time = t_;
  return s;
}

std::unique_ptr<Stepper> make_mri_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                          const Real* y0) {
  return std::make_unique<MriStepper>(system, opts, t0, y0);
}

}  // namespace detail
}  // namespace sphark
