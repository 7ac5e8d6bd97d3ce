// Where the per-particle steppers pay (issue #17), on the separated-scales oscillator case
// (sphark/study/oscillator_study.hpp: 60 slow + 4 fast oscillators, every mode excited, t = 2):
// the cheapest setting of each stepper that reaches an error level, and the measured floor of
// the ratio of their particle evaluations (deterministic runs; the numbers of the chart in
// docs/time_integration.md, "Where MRIStep pays: the oscillator model").
#include <gtest/gtest.h>

#include <cstdio>

#include "sphark/study/oscillator_study.hpp"

namespace sphark::test {
namespace {

// The first setting (0, 1, ...) whose error is at most `level`.
OscillatorStudyRun cheapest(OscillatorMethod m, Real level) {
  for (int k = 0; k < 8; ++k) {
    const OscillatorStudyRun r = run_oscillator_study(m, k);
    if (r.error <= level) {
      std::printf("%s: setting %d, %ld particle evaluations, error %.3g (level %g)\n", oscillator_method_name(m).c_str(),
                  k, r.particle_evals, r.error, level);
      return r;
    }
  }
  ADD_FAILURE() << oscillator_method_name(m) << " does not reach " << level;
  return {};
}

// Accuracy-bound slow steps: MRIStep (fourth order, the fast ones alone on the fast steps)
// against the global DP5 at 1e-3: 42,548 against 291,328 evaluations (6.85x).
TEST(MultiratePays, MriAgainstTheGlobalErkAtTightError) {
  const OscillatorStudyRun mri = cheapest(OscillatorMethod::MriErk45a, 1e-3);
  const OscillatorStudyRun erk = cheapest(OscillatorMethod::ErkDp5, 1e-3);
  ASSERT_GT(mri.particle_evals, 0);
  EXPECT_GE(static_cast<double>(erk.particle_evals) / static_cast<double>(mri.particle_evals), 6.8);
}

// Block steps against the global leapfrog at 0.15: 12,704 against 128,064 evaluations (10.1x:
// the slow oscillators' 64-fold longer steps, diluted by the 4 fast ones).
TEST(MultiratePays, BlocksAgainstTheGlobalLeapfrogAtLooseError) {
  const OscillatorStudyRun blocks = cheapest(OscillatorMethod::Blocks, 0.15);
  const OscillatorStudyRun leapfrog = cheapest(OscillatorMethod::Leapfrog, 0.15);
  ASSERT_GT(blocks.particle_evals, 0);
  EXPECT_GE(static_cast<double>(leapfrog.particle_evals) / static_cast<double>(blocks.particle_evals), 10.0);
}

}  // namespace
}  // namespace sphark::test
