#pragma once
// The MRIStep stepper over K levels (mri_stepper.cpp: the partition, the evaluations, the steps;
// mri_chain.cpp: the nested integrators and their C callbacks). Private to src/integrate/.
#include <memory>
#include <string>
#include <vector>

#include "mri_split.hpp"
#include "steppers.hpp"
#include "sundials_handles.hpp"

namespace sphark::detail {

class MriStepper;

// What a level's C callbacks get: the stepper and the level (stable: held by unique_ptr).
struct LevelContext {
  MriStepper* stepper;
  int level;
};

class MriStepper final : public Stepper {
 public:
  MriStepper(OdeSystem& system, const StepperOptions& opts, Real t0, const Real* y0);
  ~MriStepper() override { release(); }
  MriStepper(const MriStepper&) = delete;
  MriStepper& operator=(const MriStepper&) = delete;
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
    if (all_approx_valid()) r.insert(r.end(), approx_f_.begin(), approx_f_.end());
    return r;
  }
  // Between slow steps: MRIStep and its inner integrators start afresh at (t, new y) (their step
  // sizes are fixed; nothing else carries over), the partition is binned afresh.
  void resize(const Resized& state) override;

 private:
  int levels() const { return split_.count(); }
  bool all_approx_valid() const {
    return std::all_of(approx_valid_.begin(), approx_valid_.end(), [](bool v) { return v; });
  }
  void create(Real t0);
  void release();
  void rebuild();
  void* create_mri(int level, Real t0, N_Vector y0, MRIStepInnerStepper inner);
  MRIStepInnerStepper wrap_mri(int level);
  void check(int flag, const char* call) const;
  void repartition(Real t, const Real* y);
  void set_steps();
  int evaluate(int level, realtype t, N_Vector y, N_Vector ydot) noexcept;
  int evaluate_from(int level, realtype t, N_Vector y, N_Vector ydot) noexcept;
  int evaluate_set(int level, const std::vector<std::size_t>& set, realtype t, N_Vector y, N_Vector ydot);
  int evolve_level(int level, realtype t0, realtype tout, N_Vector y) noexcept;
  AdvanceStatus end_at_last_step(Real* y, Real& t, AdvanceStatus status);
  std::string failure_text(int flag) const;
  long steps_of(int level) const;
  static int level_cb(realtype t, N_Vector y, N_Vector ydot, void* context);
  static int step_done_cb(realtype t, N_Vector y, void* self);
  static int inner_evolve_cb(MRIStepInnerStepper s, realtype t0, realtype tout, N_Vector y);
  static int inner_full_rhs_cb(MRIStepInnerStepper s, realtype t, N_Vector y, N_Vector f, int mode);
  static int inner_reset_cb(MRIStepInnerStepper s, realtype t, N_Vector y);
  static void error_cb(int code, const char* module, const char* function, char* msg, void* self);

  OdeSystem& system_;
  const StepperOptions opts_;
  ContextPtr ctx_;
  std::vector<Real> y_;  // state after the last accepted slow step
  Real t_;
  MriSplit split_;
  std::vector<Real> h_set_;  // the fixed steps each level's integrator was given
  std::vector<std::vector<std::size_t>> sets_;  // each level's particles (ascending)
  std::vector<Real> stable_dt_;
  // The latest derivatives of each level's entries: the derivative handed to particle_stable_dt
  // (its "stepper's approximation of f"; valid once every level has been evaluated since the
  // last repartition).
  std::vector<Real> approx_f_;
  std::vector<std::vector<std::size_t>> set_entries_;
  std::vector<bool> approx_valid_;
  std::vector<long> base_steps_;  // of the memories replaced by resize()
  std::vector<LevelStats> level_stats_;
  std::vector<std::unique_ptr<LevelContext>> contexts_;
  std::vector<char> forcing_on_;  // level k's MRIStep is inside its wrapper's evolve: f_k gets the forcing
  std::vector<std::vector<Real>> level_y_;  // [k]: the state of level k's MRIStep (k = 1 .. K-2)
  long repartitions_ = 0;  // partitions that changed a set
  bool sets_valid_ = false;  // sets_ follow the split (false until the first repartition)
  int depth_ = 2;            // levels 0 .. depth_-1 have an integrator (the last an ARKStep)
  // Freed by release(): the outer MRIStep (mem_) first, then each wrapper and the MRIStep it
  // wraps (inner_[k], mems_[k], k = 1 .. K-2), then the fast ARKStep's wrapper and the ARKStep.
  ArkMemPtr fast_mem_;
  InnerStepperPtr fast_inner_;
  std::vector<MriMemPtr> mems_;            // [k]: level k's MRIStep, k = 1 .. K-2 (index 0 unused)
  std::vector<InnerStepperPtr> inner_;     // [k]: the wrapper of mems_[k]
  MriMemPtr mem_;                          // level 0
  std::string failure_, callback_error_, arkode_message_;
  bool failed_ = false, interrupted_ = false, restart_pending_ = false;
};

}  // namespace sphark::detail
