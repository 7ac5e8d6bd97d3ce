// The separated-scales work-precision study of the oscillator model (sphark/study/oscillator_study.hpp).
#include "sphark/study/oscillator_study.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "sphark/integrate/stepper.hpp"
#include "sphark/study/oscillator_model.hpp"

namespace sphark {

namespace {
constexpr int kSlow = 60, kFast = 4;
constexpr Real kFastOmega = 100, kKappa = 0.01, kTEnd = 2;
}  // namespace

std::string oscillator_method_name(OscillatorMethod m) {
  switch (m) {
    case OscillatorMethod::Leapfrog: return "leapfrog";
    case OscillatorMethod::ErkDp5: return "erk-dp5";
    case OscillatorMethod::Blocks: return "leapfrog-blocks";
    case OscillatorMethod::MriErk33a: return "mri-erk33a";
    case OscillatorMethod::MriErk45a: return "mri-erk45a";
  }
  return "?";
}

StepperOptions oscillator_study_options(OscillatorMethod m, int setting) {
  const Real c = 1.6 / std::ldexp(1.0, setting);
  StepperOptions o;
  switch (m) {
    case OscillatorMethod::Leapfrog:
      o.method = "leapfrog", o.fixed_dt = c / kFastOmega;
      break;
    case OscillatorMethod::ErkDp5:
      o.method = "ARKODE_DORMAND_PRINCE_7_4_5", o.rtol = 1e-3 / std::pow(10.0, setting), o.atol = {1e-3 * o.rtol};
      break;
    case OscillatorMethod::Blocks:
      o.method = "leapfrog-blocks", o.fixed_dt = c / 2, o.cfl_safety = c;
      break;
    case OscillatorMethod::MriErk33a:
    case OscillatorMethod::MriErk45a:
      o.method = m == OscillatorMethod::MriErk33a ? "mri-ARKODE_MRI_GARK_ERK33a" : "mri-ARKODE_MRI_GARK_ERK45a";
      o.fixed_dt = c / 2, o.mri_ratio = 64, o.mri_fast_table = "ARKODE_DORMAND_PRINCE_7_4_5", o.cfl_safety = c;
      break;
  }
  return o;
}

OscillatorStudyRun run_oscillator_study(OscillatorMethod m, int setting) {
  const std::vector<Real> w = separated_frequencies(kSlow, kFast, kFastOmega);
  OscillatorModel sys(w, kKappa);
  const std::vector<Real> y0 = excited_state(w.size());
  auto stepper = make_stepper(sys, oscillator_study_options(m, setting), 0, y0.data());
  std::vector<Real> y(y0.size());
  Real t = 0;
  if (stepper->advance(kTEnd, y.data(), t) != AdvanceStatus::Reached)
    throw std::runtime_error(oscillator_method_name(m) + ": " + stepper->failure_reason());
  const StepperStats s = stepper->stats();
  return {s.particle_evals, s.steps, oscillator_error(y, sys.exact(y0, kTEnd), w)};
}

}  // namespace sphark
