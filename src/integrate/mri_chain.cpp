// The chain of integrators of the MRIStep stepper (mri_stepper.hpp): the fastest level's ARKStep,
// each middle level's MRIStep behind a custom MRIStepInnerStepper, level 0's MRIStep; their C
// callbacks (no exception crosses them); their steps, release and rebuild.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "sphark/integrate/callback_errors.hpp"
#include "mri_stepper.hpp"

namespace sphark::detail {

// Level `level`'s MRIStep over `inner`, the coupling table of opts_.method, fixed step.
void* MriStepper::create_mri(int level, Real t0, N_Vector y0, MRIStepInnerStepper inner) {
  MriMemPtr mem(MRIStepCreate(&level_cb, nullptr, t0, y0, inner, ctx_.get()));
  if (!mem) throw std::runtime_error("MRIStepCreate failed");
  void* m = mem.get();
  check(MRIStepSetUserData(m, contexts_[static_cast<std::size_t>(level)].get()), "MRIStepSetUserData");
  check(MRIStepSetErrHandlerFn(m, &error_cb, this), "MRIStepSetErrHandlerFn");
  MRIStepCoupling table = MRIStepCoupling_LoadTableByName(opts_.method.substr(4).c_str());
  if (table == nullptr) throw std::invalid_argument("method=" + opts_.method + ": no such MRI coupling table");
  const int flag = MRIStepSetCoupling(m, table);
  MRIStepCoupling_Free(table);  // copied by MRIStepSetCoupling
  check(flag, "MRIStepSetCoupling");
  check(MRIStepSetFixedStep(m, split_.h(level)), "MRIStepSetFixedStep");
  check(MRIStepSetMaxNumSteps(m, opts_.max_steps), "MRIStepSetMaxNumSteps");
  if (level == 0) {
    check(MRIStepSetPostprocessStepFn(m, &step_done_cb), "MRIStepSetPostprocessStepFn");  // after SetUserData
    mem_ = std::move(mem);
  } else {
    mems_[static_cast<std::size_t>(level)] = std::move(mem);
  }
  return m;
}

// The inner stepper of level level-1: level `level`'s MRIStep behind a custom wrapper.
MRIStepInnerStepper MriStepper::wrap_mri(int level) {
  MRIStepInnerStepper s = nullptr;
  check(MRIStepInnerStepper_Create(ctx_.get(), &s), "MRIStepInnerStepper_Create");
  inner_[static_cast<std::size_t>(level)].reset(s);
  check(MRIStepInnerStepper_SetContent(s, contexts_[static_cast<std::size_t>(level)].get()), "MRIStepInnerStepper_SetContent");
  check(MRIStepInnerStepper_SetEvolveFn(s, &inner_evolve_cb), "MRIStepInnerStepper_SetEvolveFn");
  check(MRIStepInnerStepper_SetFullRhsFn(s, &inner_full_rhs_cb), "MRIStepInnerStepper_SetFullRhsFn");
  check(MRIStepInnerStepper_SetResetFn(s, &inner_reset_cb), "MRIStepInnerStepper_SetResetFn");
  return s;
}

// The fastest level's ARKStep (explicit table only, fixed step) and its inner-stepper wrapper,
// then the MRISteps from the deepest to level 0, each the inner stepper of the next; depth_
// levels (empty deeper levels get no integrator: their fixed steps would be vector work only).
void MriStepper::create(Real t0) {
  const int K = depth_;
  auto y0 = make_view(y_.size(), y_.data(), ctx_.get());  // copied by the Create calls
  fast_mem_.reset(ARKStepCreate(&level_cb, nullptr, t0, y0.get(), ctx_.get()));
  if (!fast_mem_) throw std::runtime_error("ARKStepCreate (MRIStep fast integrator) failed");
  void* fast = fast_mem_.get();
  check(ARKStepSetUserData(fast, contexts_[static_cast<std::size_t>(K - 1)].get()), "ARKStepSetUserData");
  check(ARKStepSetErrHandlerFn(fast, &error_cb, this), "ARKStepSetErrHandlerFn");
  if (ARKStepSetTableName(fast, "ARKODE_DIRK_NONE", opts_.mri_fast_table.c_str()) < 0)
    throw std::invalid_argument("mri_fast_table=" + opts_.mri_fast_table + ": ARKStepSetTableName rejected it");
  check(ARKStepSetFixedStep(fast, split_.h(K - 1)), "ARKStepSetFixedStep");
  // Lagrange: the default Hermite interpolant costs one more f_fast evaluation per fast step.
  check(ARKStepSetInterpolantType(fast, ARK_INTERP_LAGRANGE), "ARKStepSetInterpolantType");
  check(ARKStepSetMaxNumSteps(fast, opts_.max_steps), "ARKStepSetMaxNumSteps");
  MRIStepInnerStepper inner = nullptr;
  check(ARKStepCreateMRIStepInnerStepper(fast, &inner), "ARKStepCreateMRIStepInnerStepper");
  fast_inner_.reset(inner);
  mems_.resize(static_cast<std::size_t>(levels()));
  inner_.resize(static_cast<std::size_t>(levels()));
  level_y_.assign(static_cast<std::size_t>(levels()), y_);
  for (int k = K - 2; k >= 1; --k) {
    create_mri(k, t0, y0.get(), inner);
    inner = wrap_mri(k);
  }
  create_mri(0, t0, y0.get(), inner);
  for (int k = 0; k < levels(); ++k) h_set_[static_cast<std::size_t>(k)] = split_.h(k);
}

// Level `level`'s MRIStep from t0 (its own current time and state: like ARKStep, an inner
// stepper does not read y on entry, which is the outer method's work vector) to tout (the stop
// time), with the forcing of this stage; the result in y. Reset first, at its own state: MRIStep
// reuses the slow RHS of its last step's end as its next first stage, and that was taken with
// the previous stage's forcing (ARKStep, the fastest level, evaluates every stage afresh).
int MriStepper::evolve_level(int level, realtype t0, realtype tout, N_Vector y) noexcept {
  const auto k = static_cast<std::size_t>(level);
  void* mem = mems_[k].get();
  try {
    const VectorPtr own = make_view(level_y_[k].size(), level_y_[k].data(), ctx_.get());
    if (MRIStepReset(mem, t0, own.get()) < 0 || MRIStepSetStopTime(mem, tout) < 0) return -1;
  } catch (...) {
    callback_error_ = current_exception_message("level " + std::to_string(level) + " reset");
    return -1;
  }
  forcing_on_[k] = 1;
  realtype t_reached = 0;
  const int flag = MRIStepEvolve(mem, tout, y, &t_reached, ARK_NORMAL);
  forcing_on_[k] = 0;
  const Real* out = N_VGetArrayPointer(y);
  std::copy(out, out + level_y_[k].size(), level_y_[k].begin());
  return flag < 0 ? flag : 0;
}

int MriStepper::level_cb(realtype t, N_Vector y, N_Vector ydot, void* context) {
  const auto* c = static_cast<const LevelContext*>(context);
  return c->stepper->evaluate(c->level, t, y, ydot);
}

int MriStepper::inner_evolve_cb(MRIStepInnerStepper s, realtype t0, realtype tout, N_Vector y) {
  void* content = nullptr;
  if (MRIStepInnerStepper_GetContent(s, &content) != 0) return -1;
  const auto* c = static_cast<const LevelContext*>(content);
  return c->stepper->evolve_level(c->level, t0, tout, y);
}

int MriStepper::inner_full_rhs_cb(MRIStepInnerStepper s, realtype t, N_Vector y, N_Vector f, int) {
  void* content = nullptr;
  if (MRIStepInnerStepper_GetContent(s, &content) != 0) return -1;
  const auto* c = static_cast<const LevelContext*>(content);
  return c->stepper->evaluate_from(c->level, t, y, f);
}

// The outer method's reset to a stage it computed itself: (t, y) is valid here.
int MriStepper::inner_reset_cb(MRIStepInnerStepper s, realtype t, N_Vector y) {
  void* content = nullptr;
  if (MRIStepInnerStepper_GetContent(s, &content) != 0) return -1;
  const auto* c = static_cast<const LevelContext*>(content);
  std::vector<Real>& own = c->stepper->level_y_[static_cast<std::size_t>(c->level)];
  std::copy(N_VGetArrayPointer(y), N_VGetArrayPointer(y) + own.size(), own.begin());
  return MRIStepReset(c->stepper->mems_[static_cast<std::size_t>(c->level)].get(), t, y);
}

// Steps taken by level `level`'s integrator since it was created (none without one).
long MriStepper::steps_of(int level) const {
  long n = 0;
  if (level >= depth_) return 0;
  if (level == depth_ - 1) ARKStepGetNumSteps(fast_mem_.get(), &n);
  else MRIStepGetNumSteps(level == 0 ? mem_.get() : mems_[static_cast<std::size_t>(level)].get(), &n);
  return n;
}

// The SUNDIALS objects, outside in: each MRIStep refers to its inner stepper, which refers to the
// integrator it wraps.
void MriStepper::release() {
  mem_.reset();
  for (std::size_t k = 1; k < mems_.size(); ++k) inner_[k].reset(), mems_[k].reset();
  fast_inner_.reset();
  fast_mem_.reset();
}

// Every integrator made afresh at (t_, y_), depth_ levels (the steps so far kept in the counts).
void MriStepper::rebuild() {
  for (int k = 0; k < levels(); ++k) base_steps_[static_cast<std::size_t>(k)] += steps_of(k);
  release();
  depth_ = split_.depth();
  create(t_);
}

// Adaptive: new level steps after a repartition (ARKODE takes h = hin at every fixed step: the
// next step is that of a fresh MRIStep).
void MriStepper::set_steps() {
  for (int k = 0; k < depth_; ++k) {
    const auto ku = static_cast<std::size_t>(k);
    if (split_.h(k) == h_set_[ku]) continue;
    if (k == depth_ - 1) check(ARKStepSetFixedStep(fast_mem_.get(), split_.h(k)), "ARKStepSetFixedStep");
    else check(MRIStepSetFixedStep(k == 0 ? mem_.get() : mems_[ku].get(), split_.h(k)), "MRIStepSetFixedStep");
    h_set_[ku] = split_.h(k);
  }
}

}  // namespace sphark::detail
