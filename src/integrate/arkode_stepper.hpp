#pragma once
// Common part of the ARKODE steppers (ERKStep and ARKStep IMEX): tolerances, step bounds,
// root finding, error capture, recovery from recoverable RHS failures, statistics.
// SUNDIALS 6.4.1 has no generic ARKode* API, so each stepper supplies a table of its
// ERKStep* / ARKStep* functions (ArkodeApi). Private to src/integrate/.
#include <string>
#include <vector>

#include "sphark/integrate/stepper.hpp"
#include "sundials_handles.hpp"

namespace sphark::detail {

struct ArkodeApi {
  const char* module;
  int (*evolve)(void*, realtype, N_Vector, realtype*, int);
  int (*reset)(void*, realtype, N_Vector);
  int (*resize)(void*, N_Vector, realtype, realtype, ARKVecResizeFn, void*);
  int (*set_user_data)(void*, void*);
  int (*set_err_handler)(void*, ARKErrHandlerFn, void*);
  int (*set_postprocess_step)(void*, ARKPostProcessFn);
  int (*ss_tolerances)(void*, realtype, realtype);
  int (*sv_tolerances)(void*, realtype, N_Vector);
  int (*set_fixed_step)(void*, realtype);
  int (*set_init_step)(void*, realtype);
  int (*set_max_step)(void*, realtype);
  int (*set_stop_time)(void*, realtype);
  int (*set_max_num_steps)(void*, long);
  int (*root_init)(void*, int, ARKRootFn);
  int (*set_no_inactive_root_warn)(void*);
  int (*get_root_info)(void*, int*);
  int (*get_step_stats)(void*, long*, realtype*, realtype*, realtype*, realtype*);
  int (*get_current_step)(void*, realtype*);
  int (*get_current_time)(void*, realtype*);
  int (*get_num_step_attempts)(void*, long*);
  int (*get_num_err_test_fails)(void*, long*);
  char* (*flag_name)(long);
};

class ArkodeStepper : public Stepper {
 public:
  AdvanceStatus advance(Real t_out, Real* y, Real& t) override { return evolve_to(t_out, y, t, ARK_NORMAL); }
  AdvanceStatus step(Real t_out, Real* y, Real& t) override { return evolve_to(t_out, y, t, ARK_ONE_STEP); }
  StepperStats stats() const override;
  std::string failure_reason() const override { return failure_; }
  std::vector<int> roots_found() const override { return roots_; }
  void resize(const Resized& state) override;

 protected:
  ArkodeStepper(OdeSystem& system, const StepperOptions& opts, const ArkodeApi& api, Real t0,
                const Real* y0);
  // Creates (again) the ARKODE memory at (t0, y_last_) and configures it; mem_ points at it.
  // Called by the derived constructor, and by resize() before the first advance().
  virtual void create(Real t0) = 0;
  // Called by create() once mem_ points at the ARKODE memory it owns.
  void configure();
  // Method-specific counters (RHS evaluations, linear solves, ...).
  virtual void add_method_stats(StepperStats& s) const = 0;
  // After xxxStepResize: method-specific sizes (IMEX: its diagonal and linear solver).
  virtual void after_resize() {}
  // A vector viewing n values at data: serial, or parallel over opts_.communicator (collective).
  VectorPtr view(std::size_t n, Real* data) const {
    VectorPtr v = make_view(n, data, ctx_.get(), opts_.communicator);
    if (opts_.reproducible_norms || opts_.communicator.distributed()) make_norms_reproducible(v.get());
    return v;
  }

  // StepperOptions::interrupt, polled by the RHS callbacks before they evaluate: true (the
  // callback then returns -1 and advance() reports Interrupted). Never throws.
  bool interrupt_now() noexcept;

  // Runs a system call inside a C callback: exceptions become -1, non-zero codes are recorded.
  template <class F>
  int guarded(const char* what, Real t, F&& call) noexcept {
    try {
      const int code = call();
      if (code != 0) record(what, t, code);
      return code;
    } catch (const std::exception& e) {
      record_exception(what, t, e.what());
    } catch (...) {
      record_exception(what, t, "unknown exception");
    }
    return -1;
  }

  OdeSystem& system_;
  const StepperOptions opts_;
  const ArkodeApi& api_;
  ContextPtr ctx_;
  std::vector<Real> y_last_;  // state last returned by advance() (y0 at construction)
  void* mem_ = nullptr;       // owned by the derived class (ErkMemPtr / ArkMemPtr)

 private:
  // ARKODE's evolve to t_out (itask ARK_NORMAL: all the way; ARK_ONE_STEP: one internal step).
  AdvanceStatus evolve_to(Real t_out, Real* y, Real& t, int itask);
  void record(const char* what, Real t, int code) noexcept;
  void record_exception(const char* what, Real t, const char* message) noexcept;
  void bound_step(Real t_out);
  void set_tolerances();
  bool recover(int& consecutive);
  void restart_after_interrupt();
  AdvanceStatus end_at_last_accepted(Real* y, Real& t, AdvanceStatus status);
  std::string failure_text(int flag, Real t, int consecutive) const;
  void check(int flag, const char* call) const;
  std::string flag_name(int flag) const;
  static int roots_cb(realtype t, N_Vector y, realtype* g, void* self);
  static int step_done_cb(realtype t, N_Vector y, void* self);
  static void error_cb(int code, const char* module, const char* function, char* msg, void* self);

  std::vector<Real> atol_;
  VectorPtr atol_view_;
  bool per_entry_atol_ = false;  // SVtolerances (one atol per entry) rather than SStolerances
  Real t_last_ = 0;              // time of y_last_
  std::vector<Real> y_accepted_;  // state after the last accepted internal step
  Real t_accepted_ = 0;
  bool fixed_step_reduced_ = false;
  bool below_min_dt_ = false;  // the last recover() stopped at StepperOptions::min_dt
  bool interrupted_ = false;   // StepperOptions::interrupt stopped the current advance()
  bool restart_pending_ = false;  // interrupted: the ARKODE memory restarts at the last accepted step
  std::string floor_failure_;  // a step below StepperOptions::step_floor (or not advancing t) ended the run
  Real t_out_ = 0;             // of the current advance() (its landing step may be a sliver)
  int steps_below_floor_ = 0;  // consecutive accepted steps below StepperOptions::step_floor
  Real step_cap_ = 0;  // max step of an adaptive run during the current advance()
  int last_code_ = 0;         // last non-zero return of a system callback
  std::string callback_error_;
  std::string arkode_message_;
  std::string failure_;
  std::vector<int> roots_;
  long recoveries_ = 0;
  Real t_recovered_ = 0;  // t_accepted_ at the last recovery (progress resets the count)
  bool failed_ = false;
  bool evolved_ = false;  // xxxStepEvolve called at least once (xxxStepResize needs it)
};

}  // namespace sphark::detail
