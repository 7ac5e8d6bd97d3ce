// Leapfrog steppers, one class, two variants (both fixed dt or dt = cfl_safety x max_stable_dt).
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
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

#include "collective_checks.hpp"
#include "entry_segments.hpp"
#include "sphark/core/profile.hpp"
#include "steppers.hpp"
#include "number_text.hpp"

namespace sphark::detail {
namespace {

constexpr int kMaxHalvings = 10;     // retries of one step after recoverable RHS failures
constexpr int kMaxRootIterations = 100;
constexpr int kMaxCorrectorIterations = 30;  // Phantom's maxits

bool crossed(Real before, Real after) {
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
  std::vector<Real> resume_data() const override {  // dy_ then t_lost_
    if (!started_ || failed_) return {};
    std::vector<Real> d = dy_;
    d.push_back(t_lost_);
    return d;
  }
  std::vector<int> roots_found() const override { return roots_; }

  // The new state at t_; the next kick uses `carried` (the derivative moved with its entries)
  // or, without it, the RHS at the new state. Time, step and Kahan compensation are kept.
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
    if (state.carried) std::copy(state.carried, state.carried + n_, dy_.begin());
    else if (call("rhs", t_, [&] { return system_.rhs(t_, y_.data(), dy_.data()); }) != 0) return fail("RHS after resize");
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
      if (opts_.resume_data.size() != n_ + 1)
        return fail("resume_data has " + std::to_string(opts_.resume_data.size()) + " values, expected " +
                    std::to_string(n_ + 1));
      std::copy(opts_.resume_data.begin(), opts_.resume_data.end() - 1, dy_.begin());
      t_lost_ = opts_.resume_data.back();
    } else if (call("rhs", t_, [&] { return system_.rhs(t_, y_.data(), dy_.data()); }) != 0) {
      fail("initial RHS");
    }
    if (!g_.empty() && call("roots", t_, [&] { return system_.roots(t_, y_.data(), g_.data()); }) != 0)
      fail("initial root functions");
  }

  Real choose_dt() {
    Real dt = opts_.fixed_dt;
    if (!(dt > 0)) {
      // the derivative at y_ that the next kick uses (FSAL: from the predictor of the last step)
      dt = opts_.cfl_safety * system_.max_stable_dt(t_, y_.data(), dy_.data());
      if (opts_.max_dt > 0) dt = std::min(dt, opts_.max_dt);
      if (!(dt > 0) || !std::isfinite(dt)) {
        const std::string why = system_.last_error();
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
  int step_kdk(Real dt) {
    const Real* y = y_.data();
    const Real* dy = dy_.data();
    Real* y_new = y_new_.data();
    Real* pred = pred_.data();
    const std::size_t p0 = system_.position_offset(), v0 = system_.velocity_offset();
    for_each_entry(not_position_, [=](std::size_t k) {
      y_new[k] = y[k] + 0.5 * dt * dy[k];         // kick
      pred[k] = y_new[k] + 0.5 * dt * dy[k];      // predictor
    });
    for_each_entry({{0, system_.position_size()}}, [=](std::size_t i) {
      y_new[p0 + i] = y[p0 + i] + dt * y_new[v0 + i];  // drift
      pred[p0 + i] = y_new[p0 + i];
    });
    const Real t1 = t_ + dt;
    const int code = call("rhs", t1, [&] { return system_.rhs(t1, pred, dy_new_.data()); });
    if (code != 0) return code;
    const Real* dy_new = dy_new_.data();
    for_each_entry(not_position_, [=](std::size_t k) { y_new[k] += 0.5 * dt * dy_new[k]; });  // kick
    return opts_.velocity_tolerance > 0 ? correct_until_converged(dt, t1) : 0;
  }

  // Phantom's corrector iterations (StepperOptions::velocity_tolerance): while the kicked
  // velocities differ from the predicted ones the RHS saw, evaluate it again at the kicked
  // state (positions unchanged) and redo the second kick. Returns the RHS code, or 1
  // (recoverable: the step is retried at half the length) if kMaxCorrectorIterations do not do.
  int correct_until_converged(Real dt, Real t1) {
    const Real tol = opts_.velocity_tolerance;
    const Real* y = y_.data();
    const Real* dy = dy_.data();
    Real* y_new = y_new_.data();
    Real* pred = pred_.data();
    for (int its = 0;; ++its) {
      const Real e = predictor_difference();
      if (e <= tol) return 0;
      if (its == kMaxCorrectorIterations) {
        callback_error_ = "velocities differ from their prediction by " + at_time(e) + " x rms after " +
                          std::to_string(its) + " corrector iterations";
        return 1;
      }
      for_each_entry(not_position_, [=](std::size_t k) { pred[k] = y_new[k]; });
      const int code = call("rhs", t1, [&] { return system_.rhs(t1, pred, dy_new_.data()); });
      if (code != 0) return code;
      ++stats_.corrector_iterations;
      const Real* dy_new = dy_new_.data();
      for_each_entry(not_position_, [=](std::size_t k) { y_new[k] = (y[k] + 0.5 * dt * dy[k]) + 0.5 * dt * dy_new[k]; });
    }
  }

  // max over velocity entries |v - v*| / rms v (kicked v in y_new_, predicted v* in pred_), over
  // every rank; 0 without velocities.
  Real predictor_difference() const {
    const std::size_t v0 = system_.velocity_offset(), nv = system_.position_size();
    double d[2] = {0, 0}, count = static_cast<double>(nv);
    for (std::size_t i = 0; i < nv; ++i) {
      d[0] = std::max(d[0], std::abs(y_new_[v0 + i] - pred_[v0 + i]));
      d[1] += y_new_[v0 + i] * y_new_[v0 + i];
    }
    if (opts_.communicator.distributed()) {
      d[0] = opts_.communicator.allreduce(d[0], ReduceOp::Max);
      d[1] = opts_.communicator.allreduce(d[1], ReduceOp::Sum);
      count = opts_.communicator.allreduce(count, ReduceOp::Sum);
    }
    return d[1] > 0 ? d[0] / std::sqrt(d[1] / count) : 0;
  }

  // One "leapfrog-rev" step (header): only v is kicked, x and every other entry q drift.
  int step_reversible(Real dt) {
    const std::size_t p0 = system_.position_offset(), v0 = system_.velocity_offset();
    const std::vector<EntrySegment> each_vector_entry{{0, system_.position_size()}};
    const Real* y = y_.data();
    const Real* dy = dy_.data();
    const Real* dy_new = dy_new_.data();
    Real* y_new = y_new_.data();
    Real* pred = pred_.data();
    for_each_entry(each_vector_entry, [=](std::size_t i) {
      y_new[v0 + i] = y[v0 + i] + 0.5 * dt * dy[v0 + i];  // kick
      pred[p0 + i] = y[p0 + i] + 0.5 * dt * y_new[v0 + i];  // x_mid
      pred[v0 + i] = y_new[v0 + i];                         // v_half
    });
    for_each_entry(not_position_or_velocity_, [=](std::size_t k) { pred[k] = y[k] + 0.5 * dt * dy[k]; });  // q*
    const Real t_mid = t_ + 0.5 * dt;
    int code = call("rhs", t_mid, [&] { return system_.rhs(t_mid, pred, dy_new_.data()); });
    if (code != 0) return code;
    for_each_entry(not_position_or_velocity_, [=](std::size_t k) {
      y_new[k] = y[k] + dt * dy_new[k];  // drift of q
      pred[k] = y_new[k];
    });
    for_each_entry(each_vector_entry, [=](std::size_t i) {
      y_new[p0 + i] = y[p0 + i] + dt * y_new[v0 + i];  // drift of x
      pred[p0 + i] = y_new[p0 + i];
      pred[v0 + i] = y_new[v0 + i] + 0.5 * dt * dy[v0 + i];  // predictor of v
    });
    const Real t1 = t_ + dt;
    code = call("rhs", t1, [&] { return system_.rhs(t1, pred, dy_new_.data()); });
    if (code != 0) return code;
    for_each_entry(each_vector_entry, [=](std::size_t i) { y_new[v0 + i] += 0.5 * dt * dy_new[v0 + i]; });  // kick
    return 0;
  }

  // Recoverable RHS failure: halve dt and retry from the saved state (up to kMaxHalvings).
  bool attempt_with_retries(Real& dt) {
    for (int halvings = 0;; ++halvings) {
      const int code = step(dt);
      if (code == 0) return true;
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
  bool locate_root(Real dt) {
    if (!eval_roots(t_ + dt)) return false;
    if (!any_crossed()) return false;
    const std::vector<Real> g_end = g_new_;
    Real tau = dt;
    for (std::size_t k = 0; k < g_.size() && !failed_; ++k)
      if (crossed(g_[k], g_end[k])) tau = std::min(tau, illinois(k, dt, g_end[k]));
    if (failed_ || interrupted_) return false;
    if (step(tau) != 0) return fail("RHS during root location"), false;
    if (!eval_roots(t_ + tau)) return false;
    roots_.assign(g_.size(), 0);
    for (std::size_t k = 0; k < g_.size(); ++k)
      if (crossed(g_[k], g_new_[k])) roots_[k] = g_new_[k] > g_[k] ? 1 : -1;
    accept(tau);
    return true;
  }

  // g at the trial state y_new_ (time t) into g_new_.
  bool eval_roots(Real t) {
    if (call("roots", t, [&] { return system_.roots(t, y_new_.data(), g_new_.data()); }) == 0) return true;
    fail("root functions");
    return false;
  }

  bool any_crossed() const {
    for (std::size_t k = 0; k < g_.size(); ++k)
      if (crossed(g_[k], g_new_[k])) return true;
    return false;
  }

  // Root of g_k(step(tau)) in (0, dt]; returns the upper end of the final bracket.
  Real illinois(std::size_t k, Real dt, Real g_dt) {
    Real lo = 0, hi = dt, g_lo = g_[k], g_hi = g_dt;
    const Real tol = 100 * std::numeric_limits<Real>::epsilon() * (std::abs(t_) + dt);
    int side = 0;
    for (int it = 0; it < kMaxRootIterations && hi - lo > tol && g_hi != 0; ++it) {
      if (interrupt_now()) return hi;
      const Real tau = std::clamp(hi - g_hi * (hi - lo) / (g_hi - g_lo), lo + 0.25 * tol, hi - 0.25 * tol);
      if (step(tau) != 0) return fail("RHS during root location"), dt;
      if (!eval_roots(t_ + tau)) return dt;
      const Real g = g_new_[k];
      if (crossed(g_[k], g)) {
        hi = tau, g_hi = g;
        if (side == 1) g_lo *= 0.5;  // Illinois: halve the stale end
        side = 1;
      } else {
        lo = tau, g_lo = g;
        if (side == -1) g_hi *= 0.5;
        side = -1;
      }
    }
    return hi;
  }

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
};

}  // namespace

std::unique_ptr<Stepper> make_leapfrog_stepper(OdeSystem& system, const StepperOptions& opts,
                                               Real t0, const Real* y0) {
  return std::make_unique<LeapfrogStepper>(system, opts, t0, y0, opts.method == "leapfrog-rev");
}

}  // namespace sphark::detail
