#pragma once
// Oscillator ensembles whose reported stable steps change in time (their dynamics does not):
// only the partition moves particles between levels (repartition and restart tests); and the
// check of an option error.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "oscillator_ensemble.hpp"
#include "sphark/integrate/stepper.hpp"

namespace sphark::test {

// Particle 0 reports the stable step `step` (0.01: fast) from t_switch on.
class SwitchingEnsemble : public OscillatorEnsemble {
 public:
  explicit SwitchingEnsemble(Real t_switch, Real step = 0.01)
      : OscillatorEnsemble({1, 1, 1, 1, 1, 1, 100, 100}, 0.3), t_switch_(t_switch), step_(step) {}
  int particle_stable_dt(Real t, const Real* y, const Real* ydot, Real* dt) override {
    OscillatorEnsemble::particle_stable_dt(t, y, ydot, dt);
    if (t >= t_switch_) dt[0] = step_;
    return 0;
  }

 private:
  Real t_switch_, step_;
};

// make_stepper(sys, o, 0, y0) throws std::invalid_argument, one line, containing `what`.
inline void expect_invalid_argument(OdeSystem& sys, const StepperOptions& o, const std::vector<Real>& y0,
                                    const std::string& what) {
  try {
    make_stepper(sys, o, 0, y0.data());
    ADD_FAILURE() << "no error for " << what;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

// Particle 0 reports 0.01 on [t_on, t_off) and `after` from t_off on: with `after` within the
// hysteresis margin above a level's step it stays on the deeper level; a run that bins afresh
// would put it elsewhere (the restart must carry the partition).
class HystereticEnsemble : public OscillatorEnsemble {
 public:
  HystereticEnsemble(Real t_on, Real t_off, Real after)
      : OscillatorEnsemble({1, 1, 1, 1, 1, 1, 100, 100}, 0.3), t_on_(t_on), t_off_(t_off), after_(after) {}
  int particle_stable_dt(Real t, const Real* y, const Real* ydot, Real* dt) override {
    OscillatorEnsemble::particle_stable_dt(t, y, ydot, dt);
    if (t >= t_on_) dt[0] = t < t_off_ ? 0.01 : after_;
    return 0;
  }

 private:
  Real t_on_, t_off_, after_;
};

// Every particle's reported stable step halves from t_halve on: all move one level deeper.
class HalvingEnsemble : public OscillatorEnsemble {
 public:
  explicit HalvingEnsemble(Real t_halve) : OscillatorEnsemble({1, 1, 1, 1, 1, 1, 100, 100}, 0.3), t_(t_halve) {}
  int particle_stable_dt(Real t, const Real* y, const Real* ydot, Real* dt) override {
    OscillatorEnsemble::particle_stable_dt(t, y, ydot, dt);
    if (t >= t_)
      for (std::size_t i = 0; i < n(); ++i) dt[i] *= 0.5;
    return 0;
  }

 private:
  Real t_;
};

// Every particle's own step is the ensemble's; an evaluation of the fast particle 6 at a time in
// [t_on, t_off) bounds particle 0 to 0.01 (OdeSystem::active_stable_dt: a neighbour's bound,
// given at those events only); particles no active one bounds get +inf.
class BoundingEnsemble : public OscillatorEnsemble {
 public:
  BoundingEnsemble(Real t_on, Real t_off)
      : OscillatorEnsemble({1, 1, 1, 1, 1, 1, 100, 100}, 0.3), t_on_(t_on), t_off_(t_off) {}
  int active_stable_dt(Real t, const Real* y, const Real* ydot, std::span<const std::size_t> active, Real* dt) override {
    std::vector<Real> own(n());
    OscillatorEnsemble::particle_stable_dt(t, y, ydot, own.data());
    std::fill(dt, dt + n(), std::numeric_limits<Real>::infinity());
    for (std::size_t i : active) dt[i] = own[i];
    const bool six = std::find(active.begin(), active.end(), std::size_t{6}) != active.end();
    if (six && t >= t_on_ && t < t_off_ && std::find(active.begin(), active.end(), std::size_t{0}) == active.end())
      dt[0] = 0.01;
    return 0;
  }

 private:
  Real t_on_, t_off_;
};

}  // namespace sphark::test
