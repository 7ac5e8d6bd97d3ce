#pragma once
// stepper_study: work-precision matrix and stability limits of the time steppers on a scene.
#include <filesystem>
#include <string>
#include <vector>

#include "sphark/study/stability_limit.hpp"
#include "sphark/study/study_run.hpp"
#include "sphark/study/study_scene.hpp"

namespace sphark {

struct StudySettings {
  std::filesystem::path out;
  std::vector<std::string> adaptive_methods;  // ERK tables with an embedding, ark-imex
  std::vector<Real> rtols;
  std::vector<StudyMode> adaptive_modes;      // Capped and/or Uncapped
  std::vector<std::string> fixed_methods;     // run at every fixed CFL number (leapfrog has its own list)
  std::vector<Real> fixed_cfls;
  std::vector<Real> leapfrog_cfls;
  std::vector<std::string> leapfrog_methods{"leapfrog", "leapfrog-rev"};  // run at every leapfrog CFL
  StudyCase reference{"ARKODE_VERNER_8_5_6", StudyMode::Capped, 1e-10, 0};
  StudyCase reference_check{"ARKODE_FEHLBERG_13_7_8", StudyMode::Capped, 1e-10, 0};
  StudyLimits limits;
  std::vector<std::string> stability_methods;
  StabilitySettings stability;
  bool matrix = true, stability_run = true;
  bool resume = false;  // keep the rows of existing tables and skip their cases
  int raise_sigint_after = 0;  // testing aid: raise(SIGINT) after this many matrix cases (0: never)
};

// Writes <out>/work_precision.csv (rewritten atomically as each case finishes) and
// <out>/reference.csv (the reference run and its check). After SIGINT/SIGTERM (signals.hpp) the
// case in progress stops at its next RHS evaluation, without a row. Returns false if the
// reference failed.
bool run_work_precision(const StudyScene& scene, const StudySettings& s);
// Why `method` cannot run on the scene (leapfrog without moving particles, ark-imex without a
// stiff part), or "" if it can.
std::string unsupported(const StudyScene& scene, const std::string& method);
// Writes <out>/stability.csv (atomically, row by row; a signal stops the bisection in progress,
// which leaves no row).
void run_stability(const StudyScene& scene, const StudySettings& s);

}  // namespace sphark
