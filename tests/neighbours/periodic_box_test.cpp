// PeriodicBox: wrapping into [lo, hi) along periodic axes only, the minimum image, and wrap_all
// (the output positions of periodic scenes) agreeing with wrap point by point.
#include <gtest/gtest.h>

#include <vector>

#include "sphark/neighbours/periodic_box.hpp"

namespace sphark {
namespace {

PeriodicBox<2> box_periodic_in_x() {
  PeriodicBox<2> b;
  b.lo = Vec<2>(-0.5, -1.0);
  b.hi = Vec<2>(0.5, 2.0);
  b.periodic = {true, false};
  return b;
}

TEST(PeriodicBox, WrapMapsIntoTheBoxAlongPeriodicAxesOnly) {
  const PeriodicBox<2> b = box_periodic_in_x();
  const Vec<2> w = b.wrap(Vec<2>(4.75, 7.0));
  EXPECT_DOUBLE_EQ(w[0], -0.25);  // 4.75 - 5
  EXPECT_EQ(w[1], 7.0);           // open axis: unchanged
  EXPECT_EQ(b.wrap(Vec<2>(0.5, 0))[0], -0.5);  // hi maps to lo
  EXPECT_DOUBLE_EQ(b.wrap(Vec<2>(-3.6, 0))[0], 0.4);
  EXPECT_DOUBLE_EQ(b.minimum_image(Vec<2>(0.9, 5))[0], -0.1);
  EXPECT_EQ(b.minimum_image(Vec<2>(0.9, 5))[1], 5.0);
}

TEST(PeriodicBox, WrapAllEqualsWrapOfEachPoint) {
  const PeriodicBox<2> b = box_periodic_in_x();
  const std::vector<Real> x{4.75, 7.0, -3.6, 0.3, 0.1, -2.0, 12.5, 1.5};
  std::vector<Real> out(x.size());
  b.wrap_all(x.data(), x.size() / 2, out.data());
  for (std::size_t a = 0; a < x.size() / 2; ++a) {
    const Vec<2> w = b.wrap(Vec<2>(x[2 * a], x[2 * a + 1]));
    EXPECT_EQ(out[2 * a], w[0]);
    EXPECT_EQ(out[2 * a + 1], w[1]);
    EXPECT_GE(out[2 * a], -0.5);
    EXPECT_LT(out[2 * a], 0.5);
  }
}

}  // namespace
}  // namespace sphark
