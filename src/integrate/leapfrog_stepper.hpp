#pragma once
// The leapfrog steppers' class (private to src/integrate/): leapfrog_stepper.cpp (what the
// variants are, construction), leapfrog_steps.cpp (one KDK or reversible step, the corrector
// iterations), leapfrog_roots.cpp (root location on the leapfrog trajectory).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <vector>

#include "collective_checks.hpp"
#include "entry_segments.hpp"
#include "sphark/core/profile.hpp"
#include "steppers.hpp"
#include "number_text.hpp"

namespace sphark::detail {

inline constexpr int kMaxHalvings = 10;     // retries of one step after recoverable RHS failures
inline constexpr int kMaxRootIterations = 100;
inline constexpr int kMaxCorrectorIterations = 30;  // Phantom's maxits

inline bool crossed(Real before, Real after) {
  return (before < 0 && after >= 0) || (before > 0 && after <= 0);
}

class LeapfrogStepper final : public Stepper {
 public:
  LeapfrogStepper(OdeSystem& system, const StepperOptions& opts, Real t0, const Real* y0, bool reversible)
      : system_(system), opts_(opts), n_(system.size()), reversible_(reversible), t_(t0), y_(y0, y0 + n_),
        dy_(n_), y_new_(n_), dy_new_(n_), pred_(n_),
        g_(system.num_roots()), g_new_(system.num_roots()) {
    mark_blocks();
  }

  AdvanceStatus advance(Real t_out, Real* y, Real& t) override { return steps_to(t_out, y, t, false); }
  AdvanceStatus step(Real t_out, Real* y, Real& t) override { return steps_to(t_out, y, t, true); }

  // Steps towards t_out: all the way, or one (single).
  AdvanceStatus steps_to(Real t_out, Real* y, Real& t, bool single) {
    ScopedPhase timer(Phase::Advance);
    roots_.clear();
    if (t_out < t_) throw std::invalid_argument("t_out=" + at_time(t_out) + ": before the current time " + at_time(t_));
    if (!failed_ && !started_) start();
    interrupted_ = false;
    for (bool first = true; !failed_ && t_ < t_out && (first || !single); first = false) {
      if (interrupt_now()) break;
      Real dt = choose_dt();
      if (failed_) break;
      bool lands = t_ + dt * (1 + 1e-10) >= t_out;  // no sliver steps before t_out
      if (lands) dt = (t_out - t_) + t_lost_;
      const Real planned = dt;
      if (!attempt_with_retries(dt)) break;
      lands = lands && dt == planned;
      if (!g_.empty()) {
        if (locate_root(dt)) {
          finish(y, t);
          return AdvanceStatus::RootFound;
        }
        if (failed_ || interrupted_) break;  // (an interrupted root search keeps the state before the trial step)
      }
      accept(dt, lands ? t_out : NAN);
    }
    finish(y, t);
    if (failed_) return AdvanceStatus::Failed;
    if (interrupted_) return AdvanceStatus::Interrupted;
    return t < t_out ? AdvanceStatus::Stepped : AdvanceStatus::Reached;
  }

  StepperStats stats() const override {
    StepperStats s = stats_;
    s.current_time = t_;
    return s;
  }
  std::string failure_reason() const override { return failure_; }
  std::vector<Real> resume_data() const override {  // dy_, t_lost_, the planned stable step (NaN: none)
    if (!started_ || failed_) return {};
    std::vector<Real> d = dy_;
    d.push_back(t_lost_);
    d.push_back(planned_stable_ ? *planned_stable_ : std::numeric_limits<Real>::quiet_NaN());
    return d;
  }
  std::vector<int> roots_found() const override { return roots_; }

  // The new state at t_; the next kick uses `carried` (the derivative moved with its entries)
  // or, without it, the RHS at the new state. Time, step and Kahan compensation are kept, and
  // with `carried` the stable step planned at the end of the last step (plan_next_step).
  void resize(const Resized& state) override {
    require_everywhere(opts_.communicator, !(system_.size() > 0 && state.y == nullptr), "resize: no state");
    n_ = system_.size();
    y_.assign(state.y, state.y + n_);
    for (auto* v : {&dy_, &y_new_, &dy_new_, &pred_}) v->assign(n_, 0.0);
    mark_blocks();
    if (!started_) {
      resume_pending_ = false;  // resume_data belonged to the old state: start() evaluates the RHS at y
      return;
    }
    if (failed_) return;
    if (state.carried) {
      std::copy(state.carried, state.carried + n_, dy_.begin());
    } else {
      planned_stable_.reset();
      if (call("rhs", t_, [&] { return system_.rhs(t_, y_.data(), dy_.data()); }) != 0) return fail("RHS after resize");
    }
    if (!g_.empty() && call("roots", t_, [&] { return system_.roots(t_, y_.data(), g_.data()); }) != 0)
      fail("root functions after resize");
  }
  std::vector<Real> carried_data() const override { return started_ && !failed_ ? dy_ : std::vector<Real>{}; }

 private:
  // The entries outside the position block (kicked by KDK) and outside both the position and the
  // velocity block (drifted by leapfrog-rev), as contiguous [begin, end) segments.
  void mark_blocks() {
    const EntrySegment pos{system_.position_offset(), system_.position_offset() + system_.position_size()};
    const EntrySegment vel{system_.velocity_offset(), system_.velocity_offset() + system_.position_size()};
    not_position_ = segments_outside({pos}, n_);
    not_position_or_velocity_ = segments_outside({pos, vel}, n_);
  }

  void start() {
    started_ = true;
    if (resume_pending_ && !opts_.resume_data.empty()) {  // a restart: the derivative the interrupted run would use
      const std::size_t size = opts_.resume_data.size();  // (n_ + 1: written before the planned step)
      if (size != n_ + 1 && size != n_ + 2)
        return fail("resume_data has " + std::to_string(size) + " values, expected " + std::to_string(n_ + 2));
      std::copy(opts_.resume_data.begin(), opts_.resume_data.begin() + static_cast<std::ptrdiff_t>(n_), dy_.begin());
      t_lost_ = opts_.resume_data[n_];
      if (size == n_ + 2 && !std::isnan(opts_.resume_data[n_ + 1])) planned_stable_ = opts_.resume_data[n_ + 1];
    } else if (call("rhs", t_, [&] { return system_.rhs(t_, y_.data(), dy_.data()); }) != 0) {
      fail("initial RHS");
    }
    if (!g_.empty() && call("roots", t_, [&] { return system_.roots(t_, y_.data(), g_.data()); }) != 0)
      fail("initial root functions");
  }

  Real choose_dt() {
    Real dt = opts_.fixed_dt;
    if (!(dt > 0)) {
      const Real stable = planned_stable_ ? *planned_stable_ : system_.max_stable_dt(t_, y_.data(), dy_.data());
      const std::string why = planned_stable_ ? planned_error_ : system_.last_error();
      planned_stable_.reset();
      dt = opts_.cfl_safety * stable;
      if (opts_.max_dt > 0) dt = std::min(dt, opts_.max_dt);
      if (!(dt > 0) || !std::isfinite(dt)) {
        fail("no usable step size (cfl_safety * max_stable_dt = " + at_time(dt) + ")" + (why.empty() ? "" : ": " + why));
        return dt;
      }
    }
    steps_below_floor_ = opts_.step_floor > 0 && dt < opts_.step_floor ? steps_below_floor_ + 1 : 0;
    if (!(t_ + dt > t_)) fail("a step of dt=" + at_time(dt) + " does not advance t (t + dt == t)");
    else if (steps_below_floor_ >= kStepsBelowFloor)
      fail("a step of dt=" + at_time(dt) + ": " + std::to_string(kStepsBelowFloor) + " steps in a row below the step floor " +
           at_time(opts_.step_floor));
    return dt;
  }

  // StepperOptions::interrupt (a stop request); never throws.
  bool interrupt_now() {
    if (!interrupted_ && opts_.interrupt) {
      try {
        interrupted_ = opts_.interrupt();
      } catch (...) {
        interrupted_ = true;
      }
    }
    return interrupted_;
  }

  int step(Real dt) {
    ++stats_.attempts;
    return reversible_ ? step_reversible(dt) : step_kdk(dt);
  }

  // One KDK step of length dt from (t_, y_, dy_) into (y_new_, dy_new_). Returns the RHS code.
  int step_kdk(Real dt);

  // Phantom's corrector iterations (StepperOptions::velocity_tolerance): while the kicked
  // velocities differ from the predicted ones the RHS saw, evaluate it again at the kicked
  // state (positions unchanged) and redo the second kick. Returns the RHS code, or 1
  // (recoverable: the step is retried at half the length) if kMaxCorrectorIterations do not do,
  // or at once on a stop request (StepperOptions::interrupt: each iteration asks).
  int correct_until_converged(Real dt, Real t1);

  // max over velocity entries |v - v*| / rms v (kicked v in y_new_, predicted v* in pred_), over
  // every rank; 0 without velocities.
  Real predictor_difference() const;

  // One "leapfrog-rev" step (header): only v is kicked, x and every other entry q drift.
  int step_reversible(Real dt);

  // Recoverable RHS failure: halve dt and retry from the saved state (up to kMaxHalvings), unless
  // a stop request came (then false, interrupted_, the state as before the step).
  bool attempt_with_retries(Real& dt) {
    for (int halvings = 0;; ++halvings) {
      const int code = step(dt);
      if (code == 0) return true;
      if (code > 0 && interrupt_now()) return false;
      if (code < 0 || halvings == kMaxHalvings || 0.5 * dt < opts_.min_dt) {
        fail(code < 0 ? "fatal RHS failure"
             : halvings == kMaxHalvings
                 ? "recoverable RHS failure persists after " + std::to_string(kMaxHalvings) + " halvings of dt"
                 : "recoverable RHS failure; halving dt=" + at_time(dt) + " would fall below min_dt");
        return false;
      }
      dt *= 0.5;
      ++stats_.rhs_recoveries;
    }
  }

  // After a trial step of length dt: if some g_k changed sign, find the earliest root on the
  // leapfrog trajectory by Illinois iteration on the step length, accept the state just past
  // it (g_k has its new sign there) and return true.
  bool locate_root(Real dt);

  // g at the trial state y_new_ (time t) into g_new_.
  bool eval_roots(Real t);

  bool any_crossed() const;

  // Root of g_k(step(tau)) in (0, dt]; returns the upper end of the final bracket.
  Real illinois(std::size_t k, Real dt, Real g_dt);

  // Time advances by compensated (Kahan) summation, so that long fixed-step runs keep exact
  // step lengths; a step landing on an output time sets it exactly.
  void accept(Real dt, Real t_landed = NAN) {
    std::swap(y_, y_new_);
    std::swap(dy_, dy_new_);
    std::swap(g_, g_new_);  // g_new_ holds g at the accepted state (when there are roots)
    if (std::isnan(t_landed)) {
      const Real increment = dt - t_lost_, t_new = t_ + increment;
      t_lost_ = (t_new - t_) - increment;
      t_ = t_new;
    } else {
      t_ = t_landed;
      t_lost_ = 0;
    }
    ++stats_.steps;
    stats_.last_dt = dt;
    plan_next_step();
  }

  // max_stable_dt at the accepted state, with the derivative the next kick uses (FSAL: from the
  // predictor of the last step), for the next choose_dt: taken here, before the time loop's
  // after_step may remove particles (an accretion), as Phantom takes the next step from the
  // force pass before it accretes; a resize that carries the derivatives keeps it.
  void plan_next_step() {
    planned_stable_.reset();
    if (opts_.fixed_dt > 0) return;
    planned_stable_ = system_.max_stable_dt(t_, y_.data(), dy_.data());
    planned_error_ = system_.last_error();
  }

  void finish(Real* y, Real& t) const {
    std::copy(y_.begin(), y_.end(), y);
    t = t_;
  }

  template <class F>
  int call(const char* what, Real t, F&& f) {
    try {
      const int code = f();
      if (std::strcmp(what, "rhs") == 0) ++stats_.rhs_evals;
      if (code != 0) {
        callback_error_ = std::string(what) + " returned " + std::to_string(code) + " at t=" + at_time(t);
        const std::string reason = system_.last_error();
        if (!reason.empty()) callback_error_ += ": " + reason;
      }
      return code;
    } catch (const std::exception& e) {
      callback_error_ = std::string(what) + " threw an exception at t=" + at_time(t) + ": " + e.what();
    } catch (...) {
      callback_error_ = std::string(what) + " threw an unknown exception at t=" + at_time(t);
    }
    return -1;
  }

  void fail(const std::string& what) {
    failed_ = true;
    failure_ = std::string(reversible_ ? "leapfrog-rev: " : "leapfrog: ") + what + " at t=" + at_time(t_);
    if (!callback_error_.empty()) failure_ += "; " + callback_error_;
  }

  OdeSystem& system_;
  const StepperOptions opts_;
  std::size_t n_;
  const bool reversible_;
  Real t_;
  Real t_lost_ = 0;  // Kahan compensation of t_
  std::vector<Real> y_, dy_, y_new_, dy_new_, pred_, g_, g_new_;
  std::vector<EntrySegment> not_position_, not_position_or_velocity_;
  std::vector<int> roots_;
  StepperStats stats_;
  std::string failure_, callback_error_;
  bool started_ = false, failed_ = false, interrupted_ = false;
  int steps_below_floor_ = 0;  // consecutive steps below StepperOptions::step_floor
  bool resume_pending_ = true;  // opts_.resume_data still applies (no resize before the start)
  std::optional<Real> planned_stable_;  // plan_next_step's max_stable_dt, until choose_dt takes it
  std::string planned_error_;
};

}  // namespace sphark::detail
