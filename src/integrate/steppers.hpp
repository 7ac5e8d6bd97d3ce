#pragma once
// Constructors of the concrete steppers (options already validated by make_stepper).
#include <memory>
#include <string>

#include "sphark/integrate/stepper.hpp"

namespace sphark::detail {

std::unique_ptr<Stepper> make_erk_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                          const Real* y0);
std::unique_ptr<Stepper> make_imex_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                           const Real* y0);
// True if name is one of the ARK IMEX pairs offered (ARK324L2SA, ARK436L2SA, ...).
bool is_imex_pair(const std::string& name);

std::unique_ptr<Stepper> make_leapfrog_stepper(OdeSystem& system, const StepperOptions& opts,
                                               Real t0, const Real* y0);

// make_stepper after the option checks (collective in a distributed run), on `system` as given.
std::unique_ptr<Stepper> make_validated_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                                const Real* y0);
// A distributed run: the stepper over a CollectiveSystem around `system` (collective_system.hpp).
std::unique_ptr<Stepper> make_distributed_stepper(OdeSystem& system, const StepperOptions& opts, Real t0,
                                                  const Real* y0);

}  // namespace sphark::detail
