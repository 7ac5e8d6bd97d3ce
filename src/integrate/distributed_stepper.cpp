// A distributed run's stepper: the serial steppers, unchanged, on a CollectiveSystem (every
// answer of the system agreed over the ranks) and on SUNDIALS' parallel vectors (ArkodeStepper
// takes them from StepperOptions::communicator). The returned stepper owns the wrapper.
#include <memory>

#include "collective_system.hpp"
#include "steppers.hpp"

namespace sphark::detail {
std::unique_ptr<Stepper> make_distributed_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                                  const Real* y0) {
  auto collective = std::make_unique<CollectiveSystem>(system, opts.communicator, opts.root_reduction);
  auto inner = make_validated_stepper(*collective, opts, t0, y0);
  return std::make_unique<WrapperOwningStepper>(std::move(collective), std::move(inner));
}

}  // namespace sphark::detail
