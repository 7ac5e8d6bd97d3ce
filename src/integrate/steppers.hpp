#pragma once
// Constructors of the concrete steppers (options already validated by make_stepper).
#include <functional>
#include <memory>
#include <string>

#include "sphark/integrate/stepper.hpp"

namespace sphark::detail {

// advance() of a stepper whose step() is the unit: steps until t_out is reached or a step ends
// otherwise (root, failure, interrupt).
inline AdvanceStatus advance_by_steps(Stepper& stepper, Real t_out, Real* y, Real& t) {
  for (;;) {
    const AdvanceStatus status = stepper.step(t_out, y, t);
    if (status != AdvanceStatus::Stepped) return status;
  }
}

std::unique_ptr<Stepper> make_erk_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                          const Real* y0);
std::unique_ptr<Stepper> make_imex_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                           const Real* y0);
// True if name is one of the ARK IMEX pairs offered (ARK324L2SA, ARK436L2SA, ...).
bool is_imex_pair(const std::string& name);

// MRIStep (method "mri-<coupling table>"): multirate_stepper.hpp has its options.
std::unique_ptr<Stepper> make_mri_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                          const Real* y0);

// "leapfrog-blocks": KDK with individual power-of-two block steps (block_leapfrog_stepper.cpp).
std::unique_ptr<Stepper> make_block_leapfrog_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                                     const Real* y0);

std::unique_ptr<Stepper> make_leapfrog_stepper(OdeSystem& system, const StepperOptions& opts,
                                               Real t0, const Real* y0);

// A stepper built on a system wrapper that it owns (the guard, the collective system): forwards
// everything to the inner stepper; the wrapper outlives it.
class WrapperOwningStepper final : public Stepper {
 public:
  // particle_evals, when given, supplies StepperStats::particle_evals (the guard's count).
  WrapperOwningStepper(std::unique_ptr<OdeSystem> wrapper, std::unique_ptr<Stepper> inner,
                       std::function<long()> particle_evals = {})
      : wrapper_(std::move(wrapper)), inner_(std::move(inner)), particle_evals_(std::move(particle_evals)) {}
  AdvanceStatus advance(Real t_out, Real* y, Real& t) override { return inner_->advance(t_out, y, t); }
  AdvanceStatus step(Real t_out, Real* y, Real& t) override { return inner_->step(t_out, y, t); }
  StepperStats stats() const override {
    StepperStats s = inner_->stats();
    if (particle_evals_) s.particle_evals = particle_evals_();
    return s;
  }
  std::string failure_reason() const override { return inner_->failure_reason(); }
  std::vector<Real> resume_data() const override { return inner_->resume_data(); }
  std::vector<int> roots_found() const override { return inner_->roots_found(); }
  void resize(const Resized& state) override { inner_->resize(state); }
  std::vector<Real> carried_data() const override { return inner_->carried_data(); }

 private:
  std::unique_ptr<OdeSystem> wrapper_;  // declared first: destroyed after inner_
  std::unique_ptr<Stepper> inner_;
  std::function<long()> particle_evals_;
};

// make_stepper after the option checks (collective in a distributed run), on `system` as given.
std::unique_ptr<Stepper> make_validated_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                                const Real* y0);
// A distributed run: the stepper over a CollectiveSystem around `system` (collective_system.hpp).
std::unique_ptr<Stepper> make_distributed_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                                  const Real* y0);

}  // namespace sphark::detail
