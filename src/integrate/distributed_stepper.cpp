// A distributed run's stepper: the serial steppers, unchanged, on a CollectiveSystem (every
// answer of the system agreed over the ranks) and on SUNDIALS' parallel vectors (ArkodeStepper
// takes them from StepperOptions::communicator). This object owns the wrapper, which must
// outlive the stepper built on it.
#include <cstdint>
#include <memory>

#include "collective_system.hpp"
#include "steppers.hpp"

namespace sphark::detail {
namespace {

// The ranks agree on every interrupt poll (a signal reaches the ranks at different times): all
// stop at the same RHS evaluation, or none does.
StepperOptions collective_interrupt(StepperOptions opts) {
  if (opts.interrupt)
    opts.interrupt = [local = opts.interrupt, comm = opts.communicator] {
      return comm.allreduce(std::int64_t(local() ? 1 : 0), ReduceOp::Max) != 0;
    };
  return opts;
}

class DistributedStepper final : public Stepper {
 public:
  DistributedStepper(OdeSystem& system, const StepperOptions& opts, Real t0, const Real* y0)
      : collective_(std::make_unique<CollectiveSystem>(system, opts.communicator, opts.root_reduction)),
        inner_(make_validated_stepper(*collective_, collective_interrupt(opts), t0, y0)) {}

  AdvanceStatus advance(Real t_out, Real* y, Real& t) override { return inner_->advance(t_out, y, t); }
  StepperStats stats() const override { return inner_->stats(); }
  std::string failure_reason() const override { return inner_->failure_reason(); }
  std::vector<Real> resume_data() const override { return inner_->resume_data(); }
  std::vector<int> roots_found() const override { return inner_->roots_found(); }
  void resize(const Resized& state) override { inner_->resize(state); }
  std::vector<Real> carried_data() const override { return inner_->carried_data(); }

 private:
  std::unique_ptr<CollectiveSystem> collective_;  // declared first: destroyed after inner_
  std::unique_ptr<Stepper> inner_;
};

}  // namespace

std::unique_ptr<Stepper> make_distributed_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                                  const Real* y0) {
  return std::make_unique<DistributedStepper>(system, opts, t0, y0);
}

}  // namespace sphark::detail
