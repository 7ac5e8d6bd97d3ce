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

}  // namespace

std::unique_ptr<Stepper> make_mri_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                          const Real* y0) {
  return std::make_unique<MriStepper>(system, opts, t0, y0);
}

}  // namespace detail
}  // namespace sphark
