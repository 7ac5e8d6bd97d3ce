// MRIStep and momentum (issue #17, "Conservation"): each of f_slow and f_fast alone does not
// conserve momentum (the pair forces between a slow and a fast particle sit in different
// parts), so unlike the global RK methods (which keep every linear invariant) MRIStep conserves
// it only to the time-stepping error: the drift falls at the coupling table's order.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "pair_springs.hpp"
#include "sphark/integrate/stepper.hpp"

namespace sphark::test {
namespace {

Real momentum_drift(const StepperOptions& o) {
  PairSprings sys;
  const std::vector<Real> y0 = spring_state();
  auto stepper = make_stepper(sys, o, 0, y0.data());
  std::vector<Real> y(y0.size());
  Real t = 0;
  EXPECT_EQ(stepper->advance(10.0, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
  return std::abs(PairSprings::momentum(y) - PairSprings::momentum(y0));
}

TEST(MriConservation, GlobalErkKeepsMomentumToRoundOff) {
  StepperOptions o;
  o.method = "ARKODE_ZONNEVELD_5_3_4";
  o.fixed_dt = 0.01;
  const Real drift = momentum_drift(o);
  std::printf("global ERK: momentum drift %.3e\n", drift);
  EXPECT_LE(drift, 1e-14);
}

TEST(MriConservation, MomentumDriftFallsAtTheTablesOrder) {
  for (const std::string& table : mri_table_names()) {
    std::vector<Real> d;
    for (int k = 0; k < 4; ++k) {
      StepperOptions o;
      o.method = "mri-" + table;
      o.fixed_dt = 0.1 / (1 << k);
      o.cfl_safety = 8 * o.fixed_dt;  // soft particles slow (8h x 0.2 >= h), stiff fast (8h x 0.079 < h)
      o.mri_ratio = 8;
      o.mri_fast_table = "ARKODE_DORMAND_PRINCE_7_4_5";
      d.push_back(momentum_drift(o));
    }
    for (std::size_t k = 1; k < d.size(); ++k) {
      const Real order = std::log2(d[k - 1] / d[k]);
      std::printf("%s: momentum drift %.3e -> %.3e, order %.2f\n", table.c_str(), d[k - 1], d[k], order);
      EXPECT_GE(order, mri_table_order(table) - 0.3) << table << " halving " << k;
    }
  }
}

}  // namespace
}  // namespace sphark::test
