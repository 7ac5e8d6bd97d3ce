#pragma once
// The adapter between one scene and the stepper study (examples/stepper_study, issue 7): a
// scene builds a fresh system + initial state per run, defines the CFL unit and the errors
// against (a) the scene's exact/reference solution and (b) a reference run of the same
// particle system (time-integration error only).
//
// A scene plugs in from its own folder: src/scenes/<scene>/study_scene.cpp defines
//   void register_<scene>_study_scenes(StudySceneRegistry& r);   // r.push_back({"name", factory})
// and the build finds it (CMakeLists.txt generates the list of these calls); nothing else changes.
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/integrate/ode_system.hpp"

namespace sphark {

// One run's system. Fresh per run: systems cache neighbour lists and the last acceleration.
class StudyProblem {
 public:
  virtual ~StudyProblem() = default;
  virtual OdeSystem& system() = 0;
  virtual const std::vector<Real>& y0() const = 0;
  // Per-entry absolute tolerance of a run at rtol: rtol times each field's natural scale.
  virtual std::vector<Real> absolute_tolerance(Real rtol) const = 0;
  // Energy-like invariant for the blow-up criterion of the stability bisection.
  virtual Real energy(Real t, const Real* y) = 0;
};

struct StudySceneOptions {
  Real spacing = 0;  // particle spacing; 0 = the scene's study default
  Real t_end = 0;    // 0 = the scene's study default
  int outputs = 0;   // output (comparison) times, evenly spaced to t_end; 0 = scene default
};

class StudyScene {
 public:
  virtual ~StudyScene() = default;
  virtual std::string name() const = 0;
  virtual std::string description() const = 0;  // one line: particles, resolution, horizon
  virtual std::unique_ptr<StudyProblem> build() const = 0;
  virtual Real t_end() const = 0;
  virtual std::vector<Real> output_times() const = 0;  // increasing, last = t_end()
  // dt of CFL number 1: h / (c + |v|)max of the initial state (fixed steps are CFL x this).
  virtual Real cfl_unit() const = 0;
  // Total error at time t (space + time) against the scene's exact solution; NaN if none.
  virtual Real exact_error(Real t, const Real* y) const = 0;
  // Time-integration error of state y against the reference-run state y_ref at the same time.
  virtual Real time_error(const Real* y, const Real* y_ref) const = 0;
  // RMS position difference against y_ref, in units of the scene's length scale.
  virtual Real position_error(const Real* y, const Real* y_ref) const = 0;
  // What time_error / exact_error measure (for CSV headers and docs).
  virtual std::string error_description() const = 0;
};

using StudySceneFactory = std::function<std::unique_ptr<StudyScene>(const StudySceneOptions&)>;
struct StudySceneEntry {
  std::string name;
  StudySceneFactory make;
};
using StudySceneRegistry = std::vector<StudySceneEntry>;

// Throws std::invalid_argument (naming the option and value) for an unknown scene or bad options.
std::unique_ptr<StudyScene> make_study_scene(const std::string& name, const StudySceneOptions& options);
std::vector<std::string> study_scene_names();

}  // namespace sphark
