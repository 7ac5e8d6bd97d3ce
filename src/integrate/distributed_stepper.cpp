// A distributed run's stepper: the serial steppers, unchanged, on a CollectiveSystem (every
// answer of the system agreed over the ranks) and on SUNDIALS' parallel vectors (ArkodeStepper
// takes them from StepperOptions::communicator). The returned stepper owns the wrapper.
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

}  // namespace

std::unique_ptr<Stepper> make_distributed_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                                  const Real* y0) {
  auto collective = std::make_unique<CollectiveSystem>(system, opts.communicator, opts.root_reduction);
  auto inner = make_validated_stepper(*collective, collective_interrupt(opts), t0, y0);
  return std::make_unique<WrapperOwningStepper>(std::move(collective), std::move(inner));
}

}  // namespace sphark::detail
