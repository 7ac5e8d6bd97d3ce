// ARKODE ERKStep over any explicit Butcher table of SUNDIALS 6.4.1.
#include "arkode_stepper.hpp"
#include "steppers.hpp"

namespace sphark::detail {
namespace {

const ArkodeApi kErkApi{
    "ERKStep",
    ERKStepEvolve,
    ERKStepReset,
    ERKStepResize,
    ERKStepSetUserData,
    ERKStepSetErrHandlerFn,
    ERKStepSetPostprocessStepFn,
    ERKStepSStolerances,
    ERKStepSVtolerances,
    ERKStepSetFixedStep,
    ERKStepSetInitStep,
    ERKStepSetMaxStep,
    ERKStepSetStopTime,
    ERKStepSetMaxNumSteps,
    ERKStepRootInit,
    ERKStepSetNoInactiveRootWarn,
    ERKStepGetRootInfo,
    ERKStepGetStepStats,
    ERKStepGetCurrentStep,
    ERKStepGetCurrentTime,
    ERKStepGetNumStepAttempts,
    ERKStepGetNumErrTestFails,
    ERKStepGetReturnFlagName,
};

class ErkStepper final : public ArkodeStepper {
 public:
  ErkStepper(OdeSystem& system, const StepperOptions& opts, Real t0, const Real* y0)
      : ArkodeStepper(system, opts, kErkApi, t0, y0) {
    create(t0);
  }

 private:
  void create(Real t0) override {
    auto y0_view = view(y_last_.size(), y_last_.data());  // copied by Create
    mem_owner_.reset(ERKStepCreate(&rhs_cb, t0, y0_view.get(), ctx_.get()));
    if (!mem_owner_) throw std::runtime_error("ERKStepCreate failed");
    mem_ = mem_owner_.get();
    configure();
    if (ERKStepSetTableName(mem_, opts_.method.c_str()) < 0)
      throw std::invalid_argument("method=" + opts_.method + ": ERKStepSetTableName rejected it");
  }

  void add_method_stats(StepperStats& s) const override { ERKStepGetNumRhsEvals(mem_, &s.rhs_evals); }

  static int rhs_cb(realtype t, N_Vector y, N_Vector ydot, void* self) {
    auto* s = static_cast<ErkStepper*>(self);
    if (s->interrupt_now()) return -1;  // a stop request: advance() reports Interrupted
    return s->guarded("rhs", t, [&] {
      return s->system_.rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
    });
  }

  ErkMemPtr mem_owner_;
};

}  // namespace

std::unique_ptr<Stepper> make_erk_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                          const Real* y0) {
  return std::make_unique<ErkStepper>(system, opts, t0, y0);
}

}  // namespace sphark::detail
