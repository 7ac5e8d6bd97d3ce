// ARKODE ARKStep IMEX: f_E(t, y) = f(t, y) + c∘y explicit, f_I(t, y) = -c∘y implicit, with the
// diagonal c = system.stiff_diagonal(t, y). The Newton system (I - γ J_I) x = b, J_I = -diag(c),
// is solved exactly by a custom matrix-embedded SUNLinearSolver: x_k = b_k / (1 + γ c_k).
#include <algorithm>
#include <stdexcept>

#include "arkode_stepper.hpp"
#include "steppers.hpp"

namespace sphark::detail {
namespace {

const ArkodeApi kArkApi{
    "ARKStep",
    ARKStepEvolve,
    ARKStepReset,
    ARKStepResize,
    ARKStepSetUserData,
    ARKStepSetErrHandlerFn,
    ARKStepSetPostprocessStepFn,
    ARKStepSStolerances,
    ARKStepSVtolerances,
    ARKStepSetFixedStep,
    ARKStepSetInitStep,
    ARKStepSetMaxStep,
    ARKStepSetStopTime,
    ARKStepSetMaxNumSteps,
    ARKStepRootInit,
    ARKStepSetNoInactiveRootWarn,
    ARKStepGetRootInfo,
    ARKStepGetStepStats,
    ARKStepGetCurrentStep,
    ARKStepGetCurrentTime,
    ARKStepGetNumStepAttempts,
    ARKStepGetNumErrTestFails,
    ARKStepGetReturnFlagName,
};

// ARKODE 6.4.1 ARK pairs: implicit (DIRK) and explicit (ERK) table names of each pair.
struct ImexPair {
  const char* name;
  const char* dirk;
  const char* erk;
};
constexpr ImexPair kPairs[] = {
    {"ARK324L2SA", "ARKODE_ARK324L2SA_DIRK_4_2_3", "ARKODE_ARK324L2SA_ERK_4_2_3"},
    {"ARK436L2SA", "ARKODE_ARK436L2SA_DIRK_6_3_4", "ARKODE_ARK436L2SA_ERK_6_3_4"},
    {"ARK437L2SA", "ARKODE_ARK437L2SA_DIRK_7_3_4", "ARKODE_ARK437L2SA_ERK_7_3_4"},
    {"ARK548L2SA", "ARKODE_ARK548L2SA_DIRK_8_4_5", "ARKODE_ARK548L2SA_ERK_8_4_5"},
    {"ARK548L2SAb", "ARKODE_ARK548L2SAb_DIRK_8_4_5", "ARKODE_ARK548L2SAb_ERK_8_4_5"},
};

const ImexPair* find_pair(const std::string& name) {
  for (const auto& p : kPairs)
    if (name == p.name) return &p;
  return nullptr;
}

class ImexStepper final : public ArkodeStepper {
 public:
  ImexStepper(OdeSystem& system, const StepperOptions& opts, Real t0, const Real* y0)
      : ArkodeStepper(system, opts, kArkApi, t0, y0),
        c_(system.size(), 0.0),
        c_explicit_(system.size(), 0.0) {
    create(t0);
  }

 private:
  void create(Real t0) override {
    c_.assign(system_.size(), 0.0);
    c_explicit_.assign(system_.size(), 0.0);
    const ImexPair* pair = find_pair(opts_.imex_table);
    if (!pair) throw std::invalid_argument("imex_table=" + opts_.imex_table + ": unknown ARK pair");
    auto y0_view = view(y_last_.size(), y_last_.data());  // copied by Create
    mem_owner_.reset(ARKStepCreate(&explicit_cb, &implicit_cb, t0, y0_view.get(), ctx_.get()));
    if (!mem_owner_) throw std::runtime_error("ARKStepCreate failed");
    mem_ = mem_owner_.get();
    configure();
    if (ARKStepSetTableName(mem_, pair->dirk, pair->erk) < 0)
      throw std::runtime_error(std::string("ARKStepSetTableName failed for ") + pair->name);
    solver_.reset(make_diagonal_solver());
    if (ARKStepSetLinearSolver(mem_, solver_.get(), nullptr) < 0)
      throw std::runtime_error("ARKStepSetLinearSolver failed");
    // f_I is linear in y (c may depend on t): one exact Newton iteration per stage.
    if (ARKStepSetLinear(mem_, 1) < 0) throw std::runtime_error("ARKStepSetLinear failed");
  }

  void add_method_stats(StepperStats& s) const override {
    ARKStepGetNumRhsEvals(mem_, &s.rhs_evals, &s.rhs_evals_implicit);
    ARKStepGetNumNonlinSolvConvFails(mem_, &s.nonlinear_failures);
    s.linear_solves = linear_solves_;
  }

  // ARKStepResize recreates the Newton solver but not the linear solver interface (its work
  // vectors keep the old length): attach the diagonal solver again.
  void after_resize() override {
    c_.assign(system_.size(), 0.0);
    c_explicit_.assign(system_.size(), 0.0);
    if (ARKStepSetLinearSolver(mem_, solver_.get(), nullptr) < 0)
      throw std::runtime_error("ARKStepSetLinearSolver failed after resize");
    if (ARKStepSetLinear(mem_, 1) < 0) throw std::runtime_error("ARKStepSetLinear failed after resize");
  }

  // f_E = f + c∘y
  static int explicit_cb(realtype t, N_Vector y, N_Vector ydot, void* self) {
    auto* s = static_cast<ImexStepper*>(self);
    if (s->interrupt_now()) return -1;  // a stop request: advance() reports Interrupted
    const Real* yv = N_VGetArrayPointer(y);
    Real* f = N_VGetArrayPointer(ydot);
    const int code = s->guarded("rhs", t, [&] { return s->system_.rhs(t, yv, f); });
    if (code != 0) return code;
    std::vector<Real>& c = s->c_explicit_;
    const int c_code = s->guarded("stiff_diagonal", t, [&] { return s->system_.stiff_diagonal(t, yv, c.data()); });
    if (c_code != 0) return c_code;
    for (std::size_t k = 0; k < c.size(); ++k) f[k] += c[k] * yv[k];
    return 0;
  }

  // f_I = -c∘y; c is kept for the linear solve that follows in the same stage.
  static int implicit_cb(realtype t, N_Vector y, N_Vector ydot, void* self) {
    auto* s = static_cast<ImexStepper*>(self);
    const Real* yv = N_VGetArrayPointer(y);
    Real* f = N_VGetArrayPointer(ydot);
    const int code = s->guarded("stiff_diagonal", t, [&] { return s->system_.stiff_diagonal(t, yv, s->c_.data()); });
    if (code != 0) return code;
    for (std::size_t k = 0; k < s->c_.size(); ++k) f[k] = -s->c_[k] * yv[k];
    return 0;
  }

  SUNLinearSolver make_diagonal_solver() {
    SUNLinearSolver ls = SUNLinSolNewEmpty(ctx_.get());
    if (!ls) throw std::runtime_error("SUNLinSolNewEmpty failed");
    ls->content = this;
    ls->ops->gettype = [](SUNLinearSolver) { return SUNLINEARSOLVER_MATRIX_EMBEDDED; };
    ls->ops->getid = [](SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; };
    ls->ops->setup = [](SUNLinearSolver, SUNMatrix) { return 0; };
    ls->ops->solve = &solve_cb;
    ls->ops->free = [](SUNLinearSolver S) {
      S->content = nullptr;  // the stepper, not owned by the solver
      SUNLinSolFreeEmpty(S);
      return 0;
    };
    return ls;
  }

  // (I + γ diag(c)) x = b  =>  x_k = b_k / (1 + γ c_k)
  static int solve_cb(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, realtype) {
    auto* s = static_cast<ImexStepper*>(S->content);
    realtype gamma = 0;
    if (ARKStepGetCurrentGamma(s->mem_, &gamma) < 0) return -1;
    const Real* bv = N_VGetArrayPointer(b);
    Real* xv = N_VGetArrayPointer(x);
    for (std::size_t k = 0; k < s->c_.size(); ++k) xv[k] = bv[k] / (1.0 + gamma * s->c_[k]);
    ++s->linear_solves_;
    return 0;
  }

  std::vector<Real> c_;           // stiff diagonal at the last f_I evaluation
  std::vector<Real> c_explicit_;  // scratch for f_E
  long linear_solves_ = 0;
  LinearSolverPtr solver_;  // declared before mem_owner_: freed after the ARKODE memory
  ArkMemPtr mem_owner_;
};

}  // namespace

bool is_imex_pair(const std::string& name) { return find_pair(name) != nullptr; }

std::unique_ptr<Stepper> make_imex_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                           const Real* y0) {
  return std::make_unique<ImexStepper>(system, opts, t0, y0);
}

}  // namespace sphark::detail
