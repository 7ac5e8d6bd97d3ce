// One step of the leapfrog steppers (leapfrog_stepper.hpp): KDK with Phantom's corrector
// iterations, and the reversible variant.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "leapfrog_stepper.hpp"

namespace sphark::detail {

int LeapfrogStepper::step_kdk(Real dt) {
  const Real* y = y_.data();
  const Real* dy = dy_.data();
  Real* y_new = y_new_.data();
  Real* pred = pred_.data();
  const std::size_t p0 = system_.position_offset(), v0 = system_.velocity_offset();
  for_each_entry(not_position_, [=](std::size_t k) {
    y_new[k] = y[k] + 0.5 * dt * dy[k];         // kick
    pred[k] = y_new[k] + 0.5 * dt * dy[k];      // predictor
  });
  for_each_entry({{0, system_.position_size()}}, [=](std::size_t i) {
    y_new[p0 + i] = y[p0 + i] + dt * y_new[v0 + i];  // drift
    pred[p0 + i] = y_new[p0 + i];
  });
  const Real t1 = t_ + dt;
  const int code = call("rhs", t1, [&] { return system_.rhs(t1, pred, dy_new_.data()); });
  if (code != 0) return code;
  const Real* dy_new = dy_new_.data();
  for_each_entry(not_position_, [=](std::size_t k) { y_new[k] += 0.5 * dt * dy_new[k]; });  // kick
  return opts_.velocity_tolerance > 0 ? correct_until_converged(dt, t1) : 0;
}

int LeapfrogStepper::correct_until_converged(Real dt, Real t1) {
  const Real tol = opts_.velocity_tolerance;
  const Real* y = y_.data();
  const Real* dy = dy_.data();
  Real* y_new = y_new_.data();
  Real* pred = pred_.data();
  for (int its = 0;; ++its) {
    const Real e = predictor_difference();
    if (e <= tol) return 0;
    if (its == kMaxCorrectorIterations) {
      callback_error_ = "velocities differ from their prediction by " + at_time(e) + " x rms after " +
                        std::to_string(its) + " corrector iterations";
      return 1;
    }
    if (interrupt_now()) return 1;  // (attempt_with_retries stops)
    for_each_entry(not_position_, [=](std::size_t k) { pred[k] = y_new[k]; });
    const int code = call("rhs", t1, [&] { return system_.rhs(t1, pred, dy_new_.data()); });
    if (code != 0) return code;
    ++stats_.corrector_iterations;
    const Real* dy_new = dy_new_.data();
    for_each_entry(not_position_, [=](std::size_t k) { y_new[k] = (y[k] + 0.5 * dt * dy[k]) + 0.5 * dt * dy_new[k]; });
  }
}

Real LeapfrogStepper::predictor_difference() const {
  const std::size_t v0 = system_.velocity_offset(), nv = system_.position_size();
  double d[2] = {0, 0}, count = static_cast<double>(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    d[0] = std::max(d[0], std::abs(y_new_[v0 + i] - pred_[v0 + i]));
    d[1] += y_new_[v0 + i] * y_new_[v0 + i];
  }
  if (opts_.communicator.distributed()) {
    d[0] = opts_.communicator.allreduce(d[0], ReduceOp::Max);
    d[1] = opts_.communicator.allreduce(d[1], ReduceOp::Sum);
    count = opts_.communicator.allreduce(count, ReduceOp::Sum);
  }
  return d[1] > 0 ? d[0] / std::sqrt(d[1] / count) : 0;
}

int LeapfrogStepper::step_reversible(Real dt) {
  const std::size_t p0 = system_.position_offset(), v0 = system_.velocity_offset();
  const std::vector<EntrySegment> each_vector_entry{{0, system_.position_size()}};
  const Real* y = y_.data();
  const Real* dy = dy_.data();
  const Real* dy_new = dy_new_.data();
  Real* y_new = y_new_.data();
  Real* pred = pred_.data();
  for_each_entry(each_vector_entry, [=](std::size_t i) {
    y_new[v0 + i] = y[v0 + i] + 0.5 * dt * dy[v0 + i];  // kick
    pred[p0 + i] = y[p0 + i] + 0.5 * dt * y_new[v0 + i];  // x_mid
    pred[v0 + i] = y_new[v0 + i];                         // v_half
  });
  for_each_entry(not_position_or_velocity_, [=](std::size_t k) { pred[k] = y[k] + 0.5 * dt * dy[k]; });  // q*
  const Real t_mid = t_ + 0.5 * dt;
  int code = call("rhs", t_mid, [&] { return system_.rhs(t_mid, pred, dy_new_.data()); });
  if (code != 0) return code;
  for_each_entry(not_position_or_velocity_, [=](std::size_t k) {
    y_new[k] = y[k] + dt * dy_new[k];  // drift of q
    pred[k] = y_new[k];
  });
  for_each_entry(each_vector_entry, [=](std::size_t i) {
    y_new[p0 + i] = y[p0 + i] + dt * y_new[v0 + i];  // drift of x
    pred[p0 + i] = y_new[p0 + i];
    pred[v0 + i] = y_new[v0 + i] + 0.5 * dt * dy[v0 + i];  // predictor of v
  });
  const Real t1 = t_ + dt;
  code = call("rhs", t1, [&] { return system_.rhs(t1, pred, dy_new_.data()); });
  if (code != 0) return code;
  for_each_entry(each_vector_entry, [=](std::size_t i) { y_new[v0 + i] += 0.5 * dt * dy_new[v0 + i]; });  // kick
  return 0;
}

}  // namespace sphark::detail
