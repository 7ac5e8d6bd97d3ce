#pragma once
// Where the multirate steppers pay (issue #17): work against precision on the oscillator model
// (oscillator_model.hpp) with two separated time scales, 60 slow oscillators (w = 1 .. 2) and 4
// fast ones (w = 100), weak all-pairs springs (kappa = 0.01), every mode excited, to t = 2,
// error against the exact solution (oscillator_error). Each stepper at settings k = 0, 1, ...
// that halve its step (or tighten its tolerance 10x):
//   leapfrog           global KDK, dt = c / 100, c = 1.6 / 2^k (stable below c = 2)
//   erk-dp5            global adaptive Dormand-Prince 5(4) (ERKStep), rtol 1e-3 / 10^k, atol 1e-3 rtol
//   leapfrog-blocks    top step c / 2, cfl_safety c: the slow ones on the top level, the fast ones
//                      on c / 128 (the global leapfrog's step below them)
//   mri-erk33a/45a     MRIStep, slow step c / 2, fast DORMAND_PRINCE_7_4_5 at c / 128 (cfl_safety c:
//                      the fast ones' steps c / 100 bound it)
// Used by bench/multirate_oscillators.cpp (the chart) and tests/multirate/multirate_pays_test.cpp.
#include <string>

#include "sphark/integrate/stepper_options.hpp"

namespace sphark {

enum class OscillatorMethod { Leapfrog, ErkDp5, Blocks, MriErk33a, MriErk45a };

// "leapfrog", "erk-dp5", "leapfrog-blocks", "mri-erk33a", "mri-erk45a"
std::string oscillator_method_name(OscillatorMethod m);
StepperOptions oscillator_study_options(OscillatorMethod m, int setting);

struct OscillatorStudyRun {
  long particle_evals = 0, steps = 0;
  Real error = 0;
};
// One run to t = 2 of the separated-scales case; throws std::runtime_error if it fails.
OscillatorStudyRun run_oscillator_study(OscillatorMethod m, int setting);

}  // namespace sphark
