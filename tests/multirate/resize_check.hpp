#pragma once
// resize() between slow steps (the time loop's particle changes), here to the same state: the
// run goes on as a fresh stepper at (t1, y(t1)) would, bit for bit, and counts its steps on.
#include <gtest/gtest.h>

#include <vector>

#include "sphark/integrate/stepper.hpp"

namespace sphark::test {

template <class MakeSystem>
void expect_resize_continues_as_fresh(MakeSystem make_system, const StepperOptions& o, const std::vector<Real>& y0,
                                      Real t1, Real t2, long expected_steps) {
  auto a_sys = make_system(), b_sys = make_system();
  auto a = make_stepper(a_sys, o, 0, y0.data());
  std::vector<Real> y1(y0.size()), ya(y0.size()), yb(y0.size());
  Real t = 0;
  ASSERT_EQ(a->advance(t1, y1.data(), t), AdvanceStatus::Reached);
  a->resize({y1.data(), nullptr, nullptr});
  ASSERT_EQ(a->advance(t2, ya.data(), t), AdvanceStatus::Reached) << a->failure_reason();
  EXPECT_EQ(a->stats().steps, expected_steps);
  auto b = make_stepper(b_sys, o, t1, y1.data());
  ASSERT_EQ(b->advance(t2, yb.data(), t), AdvanceStatus::Reached);
  for (std::size_t k = 0; k < ya.size(); ++k) EXPECT_EQ(ya[k], yb[k]) << "entry " << k;
}

}  // namespace sphark::test
