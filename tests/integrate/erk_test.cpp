// ARKODE ERKStep: every explicit table of SUNDIALS 6.4.1 on the harmonic oscillator.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <arkode/arkode_butcher_erk.h>

#include "test_systems.hpp"

namespace sphark::test {
namespace {

// |y(T) - exact| (max norm) for x'' = -x, x(0) = 1, v(0) = 0.
Real oscillator_error(const StepperOptions& opts, Real T, StepperStats* stats = nullptr) {
  Oscillator sys;
  const Real y0[2] = {1, 0};
  auto stepper = make_stepper(sys, opts, 0, y0);
  Real y[2], t = 0;
  EXPECT_EQ(stepper->advance(T, y, t), AdvanceStatus::Reached) << stepper->failure_reason();
  EXPECT_EQ(t, T);
  if (stats) *stats = stepper->stats();
  return std::max(std::abs(y[0] - std::cos(T)), std::abs(y[1] + std::sin(T)));
}

TEST(ErkTables, ListsAllFifteenTablesOfSundials641) {
  const auto names = erk_table_names();
  ASSERT_EQ(names.size(), 15u);
  EXPECT_EQ(names.front(), "ARKODE_HEUN_EULER_2_1_2");
  EXPECT_EQ(names.back(), "ARKODE_ARK548L2SAb_ERK_8_4_5");
  for (const auto& name : names) {
    ARKodeButcherTable table = ARKodeButcherTable_LoadERKByName(name.c_str());
    ASSERT_NE(table, nullptr) << name;  // every name is one ARKODE knows
    ARKodeButcherTable_Free(table);
    EXPECT_EQ(erk_table_has_embedding(name), name != "ARKODE_KNOTH_WOLKE_3_3") << name;
  }
}

// Adaptive: every embedded table reaches t = 1, and the error falls as rtol tightens.
TEST(ErkTables, EveryEmbeddedTableConvergesAsRtolTightens) {
  for (const auto& name : erk_table_names()) {
    if (!erk_table_has_embedding(name)) continue;
    Real previous = INFINITY;
    for (Real rtol : {1e-4, 1e-6, 1e-8}) {
      StepperOptions o = options(name, rtol);
      o.atol = {rtol * 1e-2, rtol * 1e-2};  // per-entry vector
      const Real err = oscillator_error(o, 1.0);
      std::printf("%-32s rtol=%g error=%.3e\n", name.c_str(), rtol, err);
      EXPECT_LT(err, 10 * rtol) << name << " rtol=" << rtol;
      EXPECT_LT(err, previous) << name << " rtol=" << rtol;
      previous = err;
    }
  }
}

// Observed order with fixed steps h = T/N, N = n0, 2 n0, 4 n0 on T = 4. Table names read
// STAGES_EMBEDDING-ORDER_ORDER (FEHLBERG_13_7_8 is of order 8).
Real observed_order(const std::string& name, int n0) {
  const Real T = 4;
  Real e1 = oscillator_error(options(name, 1e-6, T / n0), T);
  Real e2 = oscillator_error(options(name, 1e-6, T / (2 * n0)), T);
  Real e3 = oscillator_error(options(name, 1e-6, T / (4 * n0)), T);
  const Real p12 = std::log2(e1 / e2), p23 = std::log2(e2 / e3);
  std::printf("%-32s N=%d errors %.3e %.3e %.3e orders %.3f %.3f\n", name.c_str(), n0, e1, e2, e3, p12, p23);
  return p23;
}

TEST(ErkTables, FixedStepOrderMatchesNominal) {
  struct Case {
    const char* name;
    int order, n0;
  };
  const Case cases[] = {
      {"ARKODE_HEUN_EULER_2_1_2", 2, 40},     {"ARKODE_BOGACKI_SHAMPINE_4_2_3", 3, 40},
      {"ARKODE_KNOTH_WOLKE_3_3", 3, 40},      {"ARKODE_ZONNEVELD_5_3_4", 4, 40},
      {"ARKODE_DORMAND_PRINCE_7_4_5", 5, 20}, {"ARKODE_VERNER_8_5_6", 6, 10},
      {"ARKODE_FEHLBERG_13_7_8", 8, 5},
  };
  for (const auto& c : cases) EXPECT_NEAR(observed_order(c.name, c.n0), c.order, 0.3) << c.name;
}

TEST(ErkStepper, StatsCountStepsAndRhsEvaluations) {
  StepperStats st;
  oscillator_error(options("ARKODE_DORMAND_PRINCE_7_4_5", 1e-6, 0.01), 1.0, &st);
  EXPECT_EQ(st.steps, 100);
  EXPECT_EQ(st.attempts, 100);
  EXPECT_EQ(st.error_test_failures, 0);
  // ERKStep 6.4.1 evaluates all 7 stages (no FSAL reuse), plus full-RHS calls for its
  // interpolant at the start and at the stop time.
  EXPECT_GE(st.rhs_evals, 7 * 100);
  EXPECT_LE(st.rhs_evals, 7 * 100 + 2);
  EXPECT_DOUBLE_EQ(st.current_time, 1.0);
  EXPECT_NEAR(st.last_dt, 0.01, 1e-12);
}

TEST(ErkStepper, OutputTimesInSequenceContinueTheRun) {
  Oscillator sys;
  const Real y0[2] = {1, 0};
  auto stepper = make_stepper(sys, options("ARKODE_VERNER_8_5_6", 1e-10), 0, y0);
  Real y[2], t = 0;
  for (int i = 1; i <= 20; ++i) {
    ASSERT_EQ(stepper->advance(0.5 * i, y, t), AdvanceStatus::Reached);
    EXPECT_EQ(t, 0.5 * i);
    EXPECT_NEAR(y[0], std::cos(t), 1e-8);
    EXPECT_NEAR(y[1], -std::sin(t), 1e-8);
  }
  ASSERT_EQ(stepper->advance(10.0, y, t), AdvanceStatus::Reached);  // t_out == t: no step
  EXPECT_NEAR(y[0], std::cos(10.0), 1e-8);
}

}  // namespace
}  // namespace sphark::test
