// ARKODE ARKStep IMEX with the custom diagonal linear solver.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <arkode/arkode_butcher_dirk.h>

#include <cmath>
#include <cstdio>

#include "test_systems.hpp"

namespace sphark::test {
namespace {

struct Result {
  AdvanceStatus status;
  Real error;      // max of |x - cos t|, |v + sin t|
  Real psi_error;  // |psi - psi_exact| * c (relative to the size of psi)
  StepperStats stats;
};

// psi_atol in units of the size of psi (1/c).
Result damped(StepperOptions opts, Real c, Real T, Real psi_atol = 1e-4) {
  DampedOscillator sys(c);
  const Real y0[3] = {1, 0, sys.psi(0)};
  opts.atol = {1e-10, 1e-10, psi_atol / c};  // per entry
  auto stepper = make_stepper(sys, opts, 0, y0);
  Real y[3], t = 0;
  const AdvanceStatus status = stepper->advance(T, y, t);
  return {status, std::max(std::abs(y[0] - std::cos(t)), std::abs(y[1] + std::sin(t))),
          std::abs(y[2] - sys.psi(t)) * c, stepper->stats()};
}

// psi' = x - c psi with c = 1e6 and dt = 0.01 (c dt = 1e4): the IMEX run is stable and
// accurate, the explicit run with the same fixed step is not. (x, v) converge at fourth order;
// the stiff psi at a reduced order (stage order of the ESDIRK: measured 1.9 then 1.4).
TEST(Imex, StiffDampingStableWhereErkBlowsUp) {
  const Real c = 1e6, T = 2;
  Real previous = INFINITY, previous_psi = INFINITY;
  for (Real dt : {0.02, 0.01, 0.005}) {
    const Result imex = damped(options("ark-imex", 1e-6, dt), c, T);
    std::printf("c*dt = %g: ark-imex error %.3e psi relative error %.3e (%s)\n", c * dt, imex.error,
                imex.psi_error, format_stats(imex.stats).c_str());
    ASSERT_EQ(imex.status, AdvanceStatus::Reached);
    EXPECT_LT(imex.error, previous / 12);  // fourth order: 16x per halving
    EXPECT_LT(imex.psi_error, previous_psi / 2);
    EXPECT_LT(imex.psi_error, 1e-2);
    EXPECT_EQ(imex.stats.steps, std::lround(T / dt));
    EXPECT_GT(imex.stats.linear_solves, 0);
    EXPECT_GT(imex.stats.rhs_evals_implicit, 0);
    previous = imex.error;
    previous_psi = imex.psi_error;
  }
  const Result erk = damped(options("ARKODE_DORMAND_PRINCE_7_4_5", 1e-6, 0.01), c, T);
  std::printf("DP5 fixed dt 0.01: psi relative error %.3e status %d\n", erk.psi_error, static_cast<int>(erk.status));
  EXPECT_TRUE(erk.status == AdvanceStatus::Failed || !(erk.psi_error < 1.0));
}

// Adaptive: ARKODE's step follows the slow dynamics (x, v) and the accuracy asked of psi;
// an explicit method is held at its stability bound h < 3.3 / c.
TEST(Imex, AdaptiveStiffRunFollowsTheSlowDynamics) {
  const Real c = 1e6;
  const Result imex = damped(options("ark-imex", 1e-6), c, 2.0, 1e-2);
  ASSERT_EQ(imex.status, AdvanceStatus::Reached);
  std::printf("adaptive ark-imex to t=2: error %.3e psi %.3e, %s\n", imex.error, imex.psi_error,
              format_stats(imex.stats).c_str());
  EXPECT_LT(imex.error, 1e-6);
  EXPECT_LT(imex.psi_error, 1e-2);
  const Result erk = damped(options("ARKODE_DORMAND_PRINCE_7_4_5", 1e-6), c, 0.01, 1e-2);
  std::printf("adaptive DP5 to t=0.01: %s\n", format_stats(erk.stats).c_str());
  EXPECT_GT(erk.stats.steps, 0.01 * c / 4);  // DP5 real stability interval ~ [-3.3, 0]
  // The psi error estimate of the pair is pessimistic (asked 1e-2, got ~1e-4), yet the IMEX
  // run needs over 100x fewer steps than the explicit one would on [0, 2].
  EXPECT_LT(100 * imex.stats.steps, 2.0 * c / 4);
}

// R(z) = 1 + z b^T (I - z A)^{-1} 1 of the implicit (DIRK) table of an ARK pair.
Real stability_function(const char* dirk, Real z) {
  ARKodeButcherTable B = ARKodeButcherTable_LoadDIRKByName(dirk);
  const int s = B->stages;
  Eigen::MatrixXd A(s, s);
  Eigen::VectorXd b(s);
  for (int i = 0; i < s; ++i) {
    b(i) = B->b[i];
    for (int j = 0; j < s; ++j) A(i, j) = B->A[i][j];
  }
  ARKodeButcherTable_Free(B);
  const Eigen::MatrixXd M = Eigen::MatrixXd::Identity(s, s) - z * A;
  return 1 + z * b.dot(M.partialPivLu().solve(Eigen::VectorXd::Ones(s)));
}

// For y' = -c y the explicit part f_E = f + c y vanishes, so N fixed steps of the ARK pair give
// exactly R(-c h)^N y0, provided every Newton system (I + γ diag(c)) x = b is solved exactly by
// x = b / (1 + γ c) (one Newton iteration per stage, ARKStepSetLinear).
TEST(Imex, DiagonalSolveIsExact) {
  // c h up to 10 (1 + γc up to ~5): the Newton residual form of ARKStep amplifies round-off
  // by about γc |z_pred / z|, so much stiffer entries are exact only to ~1e-8 relative.
  const std::vector<Real> c = {0.5, 10, 50, 200};
  StiffRelaxation sys(c, /*forcing=*/false);
  const Real h = 0.05, T = 1.0;
  const int n = 20;
  for (const auto& [pair, dirk] : {std::pair{"ARK324L2SA", "ARKODE_ARK324L2SA_DIRK_4_2_3"},
                                   std::pair{"ARK436L2SA", "ARKODE_ARK436L2SA_DIRK_6_3_4"},
                                   std::pair{"ARK548L2SAb", "ARKODE_ARK548L2SAb_DIRK_8_4_5"}}) {
    StepperOptions o = options("ark-imex", 1e-6, h);
    o.imex_table = pair;
    const std::vector<Real> y0(c.size(), 1.0);
    auto stepper = make_stepper(sys, o, 0, y0.data());
    std::vector<Real> y(c.size());
    Real t = 0;
    ASSERT_EQ(stepper->advance(T, y.data(), t), AdvanceStatus::Reached) << stepper->failure_reason();
    for (std::size_t k = 0; k < c.size(); ++k) {
      const Real expected = std::pow(stability_function(dirk, -c[k] * h), n);
      EXPECT_NEAR(y[k], expected, 1e-12 * std::abs(expected)) << pair << " c=" << c[k];
    }
    EXPECT_EQ(stepper->stats().steps, n) << pair;
    EXPECT_EQ(stepper->stats().nonlinear_failures, 0) << pair;
  }
}

TEST(Imex, SystemWithoutStiffPartIsRejected) {
  Oscillator sys;
  const Real y0[2] = {1, 0};
  try {
    make_stepper(sys, options("ark-imex"), 0, y0);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("method=ark-imex"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sphark::test
