// MRIStep on the oscillator ensemble (frequencies 1 and 100): the error at a fixed end time
// falls at the coupling table's order as the slow step halves (issue #17, "Order").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "oscillator_ensemble.hpp"
#include "sphark/integrate/stepper.hpp"

namespace sphark::test {
namespace {

// 6 slow oscillators (w = 1) and 2 fast ones (w = 100), coupled by springs kappa.
OscillatorEnsemble ensemble() { return OscillatorEnsemble({1, 1, 1, 1, 1, 1, 100, 100}, 0.3); }

std::vector<Real> initial_state(const OscillatorEnsemble& sys, bool slow_manifold) {
  const std::vector<Real> y = excited_state(sys.n());
  return slow_manifold ? sys.project_below(y, 10) : y;
}

StepperOptions mri(const std::string& table, Real h, int ratio) {
  StepperOptions o;
  o.method = "mri-" + table;
  o.fixed_dt = h;
  o.mri_ratio = ratio;
  o.mri_fast_table = "ARKODE_DORMAND_PRINCE_7_4_5";
  return o;
}

// Errors at t = 1 for slow steps h0, h0/2, h0/4, h0/8 (fixed slow/fast ratio).
std::vector<Real> errors(const std::string& table, bool slow_manifold, Real h0, int ratio) {
  std::vector<Real> out;
  for (int k = 0; k < 4; ++k) {
    OscillatorEnsemble sys = ensemble();
    const std::vector<Real> y0 = initial_state(sys, slow_manifold);
    auto stepper = make_stepper(sys, mri(table, h0 / (1 << k), ratio), 0, y0.data());
    std::vector<Real> y(y0.size());
    Real t = 0;
    EXPECT_EQ(stepper->advance(1.0, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
    out.push_back(max_error(y, sys.exact(y0, 1.0)));
  }
  return out;
}

void expect_order(const std::string& table, bool slow_manifold, Real h0, int ratio) {
  const std::vector<Real> e = errors(table, slow_manifold, h0, ratio);
  const int p = mri_table_order(table);
  for (std::size_t k = 1; k < e.size(); ++k) {
    const Real order = std::log2(e[k - 1] / e[k]);
    std::printf("%s %s h0=%g ratio=%d: error %.3e -> %.3e, order %.2f (table %d)\n", table.c_str(),
                slow_manifold ? "slow-manifold" : "excited", h0, ratio, e[k - 1], e[k], order, p);
    EXPECT_GE(order, p - 0.3) << table << " halving " << k;
  }
}

TEST(MriOrder, MisKw3SlowManifold) { expect_order("ARKODE_MIS_KW3", true, 0.1, 20); }
TEST(MriOrder, Erk33aSlowManifold) { expect_order("ARKODE_MRI_GARK_ERK33a", true, 0.1, 20); }
TEST(MriOrder, Erk45aSlowManifold) { expect_order("ARKODE_MRI_GARK_ERK45a", true, 0.1, 20); }
TEST(MriOrder, MisKw3Excited) { expect_order("ARKODE_MIS_KW3", false, 0.1, 20); }
TEST(MriOrder, Erk33aExcited) { expect_order("ARKODE_MRI_GARK_ERK33a", false, 0.1, 20); }
TEST(MriOrder, Erk45aExcited) { expect_order("ARKODE_MRI_GARK_ERK45a", false, 0.1, 20); }

}  // namespace
}  // namespace sphark::test
