// The SPMHD scenes of the stepper study on tiny set-ups: the cleaning disc (the cleaning energy
// is an exact invariant of the sigma = 0 ODE) and Orszag-Tang.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sphark/integrate/stepper.hpp"
#include "sphark/study/study_run.hpp"

namespace sphark {
namespace {

// 120 particles (spacing 0.16), 4 outputs to t = 2 (4 CFL units h/c_h). Above rtol 1e-5 the
// energy change is already far below the tolerance and no longer follows it (DP5: 1.3e-5 at
// rtol 1e-3, 1e-4 and 1e-5): the test starts there.
TEST(StepperStudyDisc, CleaningEnergyChangeFallsAsRtolTightens) {
  auto scene = make_study_scene("disc", {0.16, 2.0, 4});
  Real previous = INFINITY;
  for (Real rtol : {1e-5, 1e-7, 1e-9}) {
    const StudyResult r = run_study_case(*scene, {"ARKODE_DORMAND_PRINCE_7_4_5", StudyMode::Uncapped, rtol, 0}, {});
    ASSERT_TRUE(r.ok()) << r.failure;
    const Real e = study_errors(*scene, r, r).exact;  // max |E_c(t) - E_c(0)| / E_c(0)
    std::printf("disc DP5 uncapped rtol %.0e: cleaning energy change %.3e (%ld RHS)\n", rtol, e, r.stats.rhs_evals);
    EXPECT_LT(e, previous / 10) << "rtol " << rtol;  // two decades of rtol buy at least one of error
    previous = e;
  }
}

TEST(StepperStudyDisc, DampedDiscImexAgreesWithErk) {
  auto scene = make_study_scene("disc_damped", {0.16, 2.0, 4});
  const Real rtol = 1e-6;
  const StudyResult erk = run_study_case(*scene, {"ARKODE_DORMAND_PRINCE_7_4_5", StudyMode::Uncapped, rtol, 0}, {});
  const StudyResult imex = run_study_case(*scene, {"ark-imex", StudyMode::Uncapped, rtol, 0}, {});
  ASSERT_TRUE(erk.ok() && imex.ok()) << erk.failure << imex.failure;
  const StudyErrors d = study_errors(*scene, imex, erk);
  std::printf("disc_damped DP5 vs ark-imex rtol %.0e: energy %.3e, field %.3e\n", rtol, d.time, d.position);
  EXPECT_TRUE(std::isnan(d.exact));  // no exact solution with damping
  EXPECT_LT(d.time, 10 * rtol);
  EXPECT_LT(d.position, 10 * rtol);
  EXPECT_GT(imex.stats.rhs_evals_implicit, 0);
}

// 16 x 18 = 288 particles to t = 0.05.
TEST(StepperStudyOrszagTang, ErkAndImexAgreeWithinTolerance) {
  auto scene = make_study_scene("orszag_tang", {1.0 / 16, 0.05, 2});
  const Real rtol = 1e-6;
  const StudyResult erk = run_study_case(*scene, {"ARKODE_DORMAND_PRINCE_7_4_5", StudyMode::Uncapped, rtol, 0}, {});
  const StudyResult imex = run_study_case(*scene, {"ark-imex", StudyMode::Uncapped, rtol, 0}, {});
  const StudyResult lf = run_study_case(*scene, {"leapfrog-rev", StudyMode::Fixed, 0, 0.1}, {});
  ASSERT_TRUE(erk.ok() && imex.ok() && lf.ok()) << erk.failure << imex.failure << lf.failure;
  const StudyErrors d = study_errors(*scene, imex, erk);
  const StudyErrors l = study_errors(*scene, lf, erk);
  std::printf("orszag_tang DP5 vs ark-imex rtol %.0e: L1 density %.3e, positions %.3e; leapfrog-rev CFL 0.1: %.3e\n",
              rtol, d.time, d.position, l.time);
  EXPECT_LT(d.time, 10 * rtol);
  EXPECT_LT(d.position, 10 * rtol);
  EXPECT_LT(l.time, 1e-3);  // a second-order run at a tenth of the CFL unit is close too
  EXPECT_GT(imex.stats.rhs_evals_implicit, 0);
}

TEST(StepperStudy, UnknownSceneIsAnError) {
  EXPECT_THROW(make_study_scene("nope", {}), std::invalid_argument);
  const auto names = study_scene_names();
  for (const char* n : {"drop", "disc", "disc_damped", "orszag_tang"})
    EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
}

}  // namespace
}  // namespace sphark
