#pragma once
// The OdeSystem a stepper sees in a distributed run: the scheme's own system, with every
// answer that steers the stepper made the same on all ranks (integrate/stepper.hpp):
//   rhs / stiff_diagonal   the most severe return code of any rank (Communicator::agree), the
//                          failing ranks' messages in last_error(); an exception in the scheme
//                          is caught here first, so that every rank reaches the reduction;
//   max_stable_dt          the minimum over the ranks (NaN if any rank's is NaN);
//   roots                  each g_k reduced by StepperOptions::root_reduction (default min),
//                          together with the return code, in one Allreduce.
// One small Allreduce per call; the rest forwards (ForwardingSystem). Private to src/integrate/.
#include <string>
#include <vector>

#include "sphark/integrate/forwarding_system.hpp"
#include "sphark/parallel/communicator.hpp"

namespace sphark::detail {

class CollectiveSystem final : public ForwardingSystem {
 public:
  CollectiveSystem(OdeSystem& inner, Communicator comm, std::vector<ReduceOp> root_reduction);

  int rhs(Real t, const Real* y, Real* ydot) override;
  int stiff_diagonal(Real t, const Real* y, Real* c) override;
  Real max_stable_dt(Real t, const Real* y, const Real* ydot) override;
  int roots(Real t, const Real* y, Real* g) override;
  std::string last_error() const override { return error_; }

 private:
  template <class F>
  int local_call(const char* what, F&& f) noexcept;  // f's code, or -1 after an exception
  int agreed(int code);                              // the collective code, error_ set

  Communicator comm_;
  std::vector<ReduceOp> root_reduction_;
  std::vector<double> buffer_;  // roots: reduced values, capacity kept
  std::string local_error_, error_;
};

}  // namespace sphark::detail
